// Helpers shared by the fem tests: clamping and jittering the structured grids
// (test_meshes::kuhn_bar, support/test_meshes.h), and small utilities.
#pragma once

#include <array>
#include <cstdint>
#include <random>
#include <vector>

#include "engine/tet_mesh.h"
#include "support/test_meshes.h"

namespace serosa::fem::fixtures {

/// Moves interior nodes of a grid by up to `amount` x cell size in each direction (uniform).
/// Fixes every node on the x = 0 face (a clamped end).
inline void clamp_x0(TetMesh& m) {
  for (std::size_t i = 0; i < m.rest.size(); ++i) m.fixed[i] = m.rest[i].x() < 1e-12 ? 1 : 0;
}

inline void jitter_interior(TetMesh& m, double lo_x, double hi_x, double lo_y, double hi_y,
                            double lo_z, double hi_z, double amount, std::uint32_t seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> u(-amount, amount);
  for (std::size_t i = 0; i < m.rest.size(); ++i) {
    Vec3& p = m.rest[i];
    const double eps = 1e-12;
    if (p.x() > lo_x + eps && p.x() < hi_x - eps && p.y() > lo_y + eps && p.y() < hi_y - eps &&
        p.z() > lo_z + eps && p.z() < hi_z - eps)
      p += Vec3(u(rng), u(rng), u(rng));
    m.x[i] = p;
  }
}

/// A random rotation (uniform quaternion).
inline Mat3 random_rotation(std::mt19937& rng) {
  std::normal_distribution<double> n(0.0, 1.0);
  Quat q(n(rng), n(rng), n(rng), n(rng));
  q.normalize();
  return q.toRotationMatrix();
}

/// True if node i lies on the boundary of the box [lo, hi].
inline bool on_box_boundary(const Vec3& p, const Vec3& lo, const Vec3& hi) {
  const double eps = 1e-9;
  for (int c = 0; c < 3; ++c)
    if (p[c] < lo[c] + eps || p[c] > hi[c] - eps) return true;
  return false;
}

}  // namespace serosa::fem::fixtures
