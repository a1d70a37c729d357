// cut_mesh: one scissor cut of a tet mesh by the convex polygon a blade swept (paper "Cutting
// Algorithm"). Returns the change as a TopologyDelta for engine's apply(); never edits the mesh.
// docs/cutting.md explains the algorithm and lists the files of its steps.
#pragma once

#include <array>
#include <cstdint>
#include <functional>
#include <vector>

#include "cutting/convex_polygon.h"
#include "cutting/cut_types.h"
#include "engine/tet_mesh.h"
#include "engine/topology_delta.h"

namespace serosa::cutting {

/// Cuts `mesh` (classified in current positions x) by `blade`. Existing nodes never move; new
/// nodes are cut points on edges (two per edge, one per side), clones of coplanar nodes and
/// Steiner points, each with its parents and barycentric weights; rest volume is conserved to
/// rounding, per group. `query` finds candidate tets (a BVH; brute force when empty).
[[nodiscard]] CutResult cut_mesh(const TetMesh& mesh, const ConvexPolygon& blade,
                                 const CutOptions& options = {}, const TetBoxQuery& query = {});

}  // namespace serosa::cutting
