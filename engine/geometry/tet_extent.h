// The extent of tets and point sets in current positions: a tet's bounding box, the box of a set
// of points, and the longest edge of a set of tets (the length every cutter's classification
// tolerance scales with: tol = classify_rel * h).
#pragma once

#include <algorithm>
#include <cstdint>
#include <span>

#include "engine/tet_mesh.h"

namespace serosa::geometry {

/// Axis-aligned box of tet `t` in current positions mesh.x, m.
inline void tet_box(const TetMesh& mesh, const Tet& t, Vec3& lo, Vec3& hi) {
  lo = hi = mesh.x[static_cast<std::size_t>(t[0])];
  for (std::size_t k = 1; k < 4; ++k) {
    lo = lo.cwiseMin(mesh.x[static_cast<std::size_t>(t[k])]);
    hi = hi.cwiseMax(mesh.x[static_cast<std::size_t>(t[k])]);
  }
}

/// Axis-aligned box of the points `x` (m); lo = hi = 0 when there are none.
inline void point_box(std::span<const Vec3> x, Vec3& lo, Vec3& hi) {
  lo = hi = x.empty() ? Vec3::Zero() : x[0];
  for (const Vec3& p : x) {
    lo = lo.cwiseMin(p);
    hi = hi.cwiseMax(p);
  }
}

/// Longest edge of tet `t` in current positions, m.
inline double longest_edge_m(const TetMesh& mesh, const Tet& t) {
  double h = 0.0;
  for (std::size_t i = 0; i < 4; ++i)
    for (std::size_t j = i + 1; j < 4; ++j)
      h = std::max(
          h,
          (mesh.x[static_cast<std::size_t>(t[i])] - mesh.x[static_cast<std::size_t>(t[j])]).norm());
  return h;
}

/// Longest edge of the tets `ids` (indices into mesh.tets) in current positions, m; 0 if none.
inline double longest_edge_m(const TetMesh& mesh, std::span<const std::int32_t> ids) {
  double h = 0.0;
  for (const std::int32_t ti : ids)
    h = std::max(h, longest_edge_m(mesh, mesh.tets[static_cast<std::size_t>(ti)]));
  return h;
}

}  // namespace serosa::geometry
