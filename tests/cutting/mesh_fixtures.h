// Meshes for the cutting tests: single tets and structured grids (k^3 cubes, 6 tets each).
#pragma once

#include <array>
#include <cstdint>
#include <random>
#include <utility>

#include "engine/tet_mesh.h"

namespace serosa::cutting::fixtures {

/// Appends tet (a, b, c, d), swapping c and d when its rest volume is negative.
inline void add_oriented(TetMesh& m, Tet t, std::uint16_t g) {
  if (signed_volume(m.rest[t[0]], m.rest[t[1]], m.rest[t[2]], m.rest[t[3]]) < 0.0)
    std::swap(t[2], t[3]);
  m.add_tet(t, g);
}

/// A cube [0, k h]^3 of k^3 cubes, each split into 6 tets around its main diagonal (Kuhn), so
/// neighbouring cubes conform. Group 1 for x < k h / 2, else 2. Interior nodes are moved by up
/// to jitter * h in each coordinate (0: exact grid, with many exactly coplanar nodes).
inline TetMesh grid(int k, double h = 1.0, double jitter = 0.0, std::uint32_t seed = 1) {
  TetMesh m;
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> u(-jitter * h, jitter * h);
  auto id = [k](int i, int j, int l) { return (i * (k + 1) + j) * (k + 1) + l; };
  for (int i = 0; i <= k; ++i)
    for (int j = 0; j <= k; ++j)
      for (int l = 0; l <= k; ++l) {
        Vec3 p(i * h, j * h, l * h);
        const bool interior = i > 0 && i < k && j > 0 && j < k && l > 0 && l < k;
        if (interior && jitter > 0.0) p += Vec3(u(rng), u(rng), u(rng));
        m.add_node(p);
      }
  constexpr std::array<std::array<int, 3>, 6> perms{
      {{0, 1, 2}, {0, 2, 1}, {1, 0, 2}, {1, 2, 0}, {2, 0, 1}, {2, 1, 0}}};
  for (int i = 0; i < k; ++i)
    for (int j = 0; j < k; ++j)
      for (int l = 0; l < k; ++l)
        for (const auto& p : perms) {
          std::array<int, 3> c{i, j, l};
          Tet t{};
          t[0] = id(c[0], c[1], c[2]);
          for (int s = 0; s < 3; ++s) {
            ++c[p[s]];
            t[s + 1] = id(c[0], c[1], c[2]);
          }
          add_oriented(m, t, static_cast<std::uint16_t>(2 * i < k ? 1 : 2));
        }
  return m;
}

/// A box of nx x ny x nz cubes of side h (m), each split into 6 tets around its main diagonal
/// (Kuhn), all exactly on the grid. Group 1 + groups * i / nx for cube column i.
inline TetMesh box(int nx, int ny, int nz, int groups = 1, double h = 0.01) {
  TetMesh m;
  auto id = [&](int i, int j, int l) { return (i * (ny + 1) + j) * (nz + 1) + l; };
  for (int i = 0; i <= nx; ++i)
    for (int j = 0; j <= ny; ++j)
      for (int l = 0; l <= nz; ++l) m.add_node(Vec3(i * h, j * h, l * h));
  constexpr std::array<std::array<int, 3>, 6> perms{
      {{0, 1, 2}, {0, 2, 1}, {1, 0, 2}, {1, 2, 0}, {2, 0, 1}, {2, 1, 0}}};
  for (int i = 0; i < nx; ++i)
    for (int j = 0; j < ny; ++j)
      for (int l = 0; l < nz; ++l)
        for (const auto& p : perms) {
          std::array<int, 3> c{i, j, l};
          Tet t{};
          t[0] = id(c[0], c[1], c[2]);
          for (int s = 0; s < 3; ++s) {
            ++c[p[s]];
            t[s + 1] = id(c[0], c[1], c[2]);
          }
          add_oriented(m, t, static_cast<std::uint16_t>(1 + groups * i / nx));
        }
  return m;
}

/// One random tet with positive volume (not too flat), nodes in [-1, 1]^3.
inline TetMesh random_tet(std::mt19937& rng) {
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  for (;;) {
    TetMesh m;
    for (int i = 0; i < 4; ++i) m.add_node(Vec3(u(rng), u(rng), u(rng)));
    const double v = signed_volume(m.rest[0], m.rest[1], m.rest[2], m.rest[3]);
    if (std::abs(v) < 0.02) continue;
    add_oriented(m, {0, 1, 2, 3}, 1);
    return m;
  }
}

}  // namespace serosa::cutting::fixtures
