// Meshes and helpers shared by the fem tests: structured grids of 6-tet cubes (Kuhn subdivision,
// conforming across cubes), optionally jittered, and small utilities.
#pragma once

#include <array>
#include <cstdint>
#include <random>
#include <vector>

#include "engine/tet_mesh.h"

namespace serosa::fem::fixtures {

/// A grid of nx x ny x nz cubes of edge h (m) from the origin, each cut into 6 tets around its
/// main diagonal. Node (i, j, k) has id i + (nx+1) (j + (ny+1) k). Group 1 everywhere.
/// Every tet is positively oriented.
inline TetMesh grid(int nx, int ny, int nz, double hx, double hy, double hz) {
  TetMesh m;
  const auto id = [&](int i, int j, int k) { return i + (nx + 1) * (j + (ny + 1) * k); };
  for (int k = 0; k <= nz; ++k)
    for (int j = 0; j <= ny; ++j)
      for (int i = 0; i <= nx; ++i) m.add_node(Vec3(i * hx, j * hy, k * hz));
  static constexpr std::array<std::array<int, 3>, 6> perms{
      {{0, 1, 2}, {0, 2, 1}, {1, 0, 2}, {1, 2, 0}, {2, 0, 1}, {2, 1, 0}}};
  for (int k = 0; k < nz; ++k)
    for (int j = 0; j < ny; ++j)
      for (int i = 0; i < nx; ++i)
        for (const auto& p : perms) {
          std::array<int, 3> c{i, j, k};
          Tet t{};
          t[0] = id(c[0], c[1], c[2]);
          for (int s = 0; s < 3; ++s) {
            ++c[static_cast<std::size_t>(p[static_cast<std::size_t>(s)])];
            t[static_cast<std::size_t>(s) + 1] = id(c[0], c[1], c[2]);
          }
          if (signed_volume(m.rest[t[0]], m.rest[t[1]], m.rest[t[2]], m.rest[t[3]]) < 0.0)
            std::swap(t[2], t[3]);
          m.add_tet(t, 1);
        }
  return m;
}

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
