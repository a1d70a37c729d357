// Real scissor cuts for the fem tests (serosa::cutting is linked into the fem test executable
// only; fem/ itself never includes cutting/): random planar blades through a mesh's current
// positions, complete (wider than the mesh) or small (a blade a few cells wide, partial cuts).
#pragma once

#include <random>

#include "cutting/convex_polygon.h"
#include "cutting/cut_mesh.h"
#include "engine/geometry/tet_extent.h"
#include "engine/tet_mesh.h"
#include "engine/topology_delta.h"

namespace serosa::fem::fixtures {

/// A random square blade centred in the middle 60% of the mesh's current bounding box, with a
/// random normal. half_width: half the square's side, m.
inline cutting::ConvexPolygon random_blade(const TetMesh& m, double half_width, std::mt19937& rng) {
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  Vec3 lo, hi;
  geometry::point_box(m.x, lo, hi);
  const Vec3 c =
      lo + (hi - lo).cwiseProduct(Vec3(0.5 + 0.3 * u(rng), 0.5 + 0.3 * u(rng), 0.5 + 0.3 * u(rng)));
  Vec3 n(u(rng), u(rng), u(rng));
  if (n.norm() < 1e-3) n = Vec3(1.0, 0.0, 0.0);
  n.normalize();
  const Vec3 a = n.unitOrthogonal(), b = n.cross(a);
  const double h = half_width;
  return cutting::ConvexPolygon(
      {c - h * a - h * b, c + h * a - h * b, c + h * a + h * b, c - h * a + h * b});
}

/// The delta of one random cut (not applied).
inline TopologyDelta random_cut(const TetMesh& m, double half_width, std::mt19937& rng) {
  return cutting::cut_mesh(m, random_blade(m, half_width, rng)).delta;
}

}  // namespace serosa::fem::fixtures
