// Invariant checker for a SurfaceMesh against the TetMesh it describes (tests, debug builds).
#pragma once

#include <string>
#include <vector>

#include "engine/tet_mesh.h"
#include "surface/surface_mesh.h"

namespace serosa::surface {

/// Problems found, empty when valid: array sizes agree; face_cut is 0 or 1; groups ascending,
/// non-empty, tiling [0, f) in order, each face's face_group equal to its range's group; every
/// face's tet exists, has that group, and the face is one of its four faces with the outward
/// orientation; node ids are valid nodes of `mesh`; topology_version equals the mesh's. O(f log g).
/// Does not check that the faces are exactly the boundary (tests compare with a reference for
/// that).
[[nodiscard]] std::vector<std::string> validate_surface(const SurfaceMesh& s, const TetMesh& mesh);

}  // namespace serosa::surface
