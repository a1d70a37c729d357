// Boundary faces of a tet mesh (reference CPU implementation, hash-free: sort by sorted key).
// surface/ has the Thrust version for the running simulation; this one serves validation
// (serosa check), the OBJ export and tests (brute-force comparison).
#pragma once

#include <cstdint>
#include <vector>

#include "engine/math.h"
#include "engine/tet_mesh.h"

namespace serosa {

struct BoundaryFace {
  Tri nodes;                ///< node ids, counter-clockwise seen from outside (normal outward)
  std::int32_t tet = -1;    ///< the tet it belongs to
  std::uint16_t group = 0;  ///< that tet's group
};

struct FaceCensus {
  std::vector<BoundaryFace> boundary;  ///< faces used by exactly one tet, sorted by (group, key)
  std::int64_t interior = 0;           ///< faces shared by exactly two tets
  std::int64_t overshared = 0;         ///< faces shared by three or more tets (invalid mesh)
};

/// Counts every face of every tet by its sorted node ids. Outward orientation follows from the
/// owning tet's positive orientation in rest space.
[[nodiscard]] FaceCensus face_census(const TetMesh& mesh);

}  // namespace serosa
