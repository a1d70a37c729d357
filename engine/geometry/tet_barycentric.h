// Barycentric weights of a point in a tet of a mesh (current positions): where a point sits in
// the tissue, to pin it there or to interpolate what the tet's nodes carry.
#pragma once

#include <array>
#include <cmath>
#include <cstdint>
#include <optional>

#include "engine/math.h"
#include "engine/tet_mesh.h"

namespace serosa::geometry {

/// Weights of p (m) in tet t, one per node in the tet's order, summing to 1 (negative outside);
/// std::nullopt for a flat tet.
[[nodiscard]] inline std::optional<std::array<double, 4>> tet_barycentric(const Vec3& p,
                                                                          const TetMesh& mesh,
                                                                          std::int32_t t) {
  const Tet& tet = mesh.tets[static_cast<std::size_t>(t)];
  const Vec3& a = mesh.x[static_cast<std::size_t>(tet[0])];
  const Vec3& b = mesh.x[static_cast<std::size_t>(tet[1])];
  const Vec3& c = mesh.x[static_cast<std::size_t>(tet[2])];
  const Vec3& d = mesh.x[static_cast<std::size_t>(tet[3])];
  Mat3 e;
  e << b - a, c - a, d - a;
  const double det = e.determinant();
  const double scale = (b - a).norm() * (c - a).norm() * (d - a).norm();
  if (!(std::abs(det) > 1e-12 * scale)) return std::nullopt;
  const Vec3 l = e.inverse() * (p - a);
  return std::array<double, 4>{1.0 - l.sum(), l.x(), l.y(), l.z()};
}

}  // namespace serosa::geometry
