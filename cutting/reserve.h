// reserve_for_cuts: spare capacity in a mesh's per-node and per-tet arrays, so that the cuts
// after loading append to them without reallocating (a reallocation copies, and page-faults, the
// whole array: O(mesh size) inside a cut).
#pragma once

#include "engine/tet_mesh.h"

namespace serosa::cutting {

/// Spare capacity kept for cuts, as a fraction of the current counts (dimensionless). A pattern
/// cut adds about 3 tets and 1.4 nodes per tet it touches, so 0.5 lasts for cuts touching about a
/// sixth of the mesh before the next reserve. Used by reserve_for_cuts and TetBvh.
inline constexpr double kCutSpare = 0.5;

/// Ensures that every per-node array (rest, x, v, mass, fixed) and per-tet array (tets, group) of
/// `mesh` has capacity for (1 + spare) times its current size. Reserves only when less than half
/// of that spare is left, so calling it once a step costs O(1) when there is nothing to do; sizes
/// and contents are unchanged. Throws std::invalid_argument when spare is negative or not finite.
void reserve_for_cuts(TetMesh& mesh, double spare = kCutSpare);

}  // namespace serosa::cutting
