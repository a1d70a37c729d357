// Test fixtures: boxes split into tets (one cube into 5 or 6, a k x k x k grid of cubes into 6
// each), positively oriented, with known volume, surface area and boundary face count.
// Shared by tests/engine and tests/app (include "engine/box_meshes.h").
#pragma once

#include <array>
#include <cstdint>
#include <random>
#include <utility>
#include <vector>

#include "engine/math.h"
#include "engine/tet_mesh.h"

namespace serosa::fixtures {

/// Swaps the last two nodes of `t` if its volume over `pos` is negative.
inline Tet orient_positive(const std::vector<Vec3>& pos, Tet t) {
  const auto p = [&](int k) {
    return pos[static_cast<std::size_t>(t[static_cast<std::size_t>(k)])];
  };
  if (signed_volume(p(0), p(1), p(2), p(3)) < 0.0) std::swap(t[2], t[3]);
  return t;
}

/// Corner k of a cube, k = x + 2y + 4z with x, y, z in {0, 1}.
inline std::array<int, 3> corner_bits(int k) { return {k & 1, (k >> 1) & 1, (k >> 2) & 1}; }

/// The unit-ordered cube's 6 Freudenthal (Kuhn) tets along the diagonal 0 -> 7, as corner ids:
/// for each axis order (i, j, k), the path 0 -> e_i -> e_i + e_j -> 7. Translated copies of this
/// split agree on every shared face, so a grid of them is conforming.
inline std::vector<std::array<int, 4>> kuhn_tets() {
  const std::array<std::array<int, 3>, 6> orders{
      {{0, 1, 2}, {0, 2, 1}, {1, 0, 2}, {1, 2, 0}, {2, 0, 1}, {2, 1, 0}}};
  std::vector<std::array<int, 4>> out;
  for (const auto& o : orders) {
    const int a = 1 << o[0];
    const int b = a | (1 << o[1]);
    out.push_back({0, a, b, 7});
  }
  return out;
}

/// The cube's 5-tet split: the central tet on corners {1, 2, 4, 7} and the four corner tets.
inline std::vector<std::array<int, 4>> five_tets() {
  return {{1, 2, 4, 7}, {0, 1, 2, 4}, {3, 1, 2, 7}, {5, 1, 4, 7}, {6, 2, 4, 7}};
}

/// A box [lo, hi] split into one cube's tets (`split` from kuhn_tets() or five_tets()), group 1.
inline TetMesh cube_mesh(const std::vector<std::array<int, 4>>& split,
                         const Vec3& lo = Vec3::Zero(), const Vec3& hi = Vec3::Ones()) {
  TetMesh m;
  for (int k = 0; k < 8; ++k) {
    const auto b = corner_bits(k);
    m.add_node(Vec3(b[0] ? hi.x() : lo.x(), b[1] ? hi.y() : lo.y(), b[2] ? hi.z() : lo.z()));
  }
  for (const auto& t : split) m.add_tet(orient_positive(m.rest, {t[0], t[1], t[2], t[3]}), 1);
  return m;
}

/// A grid of k x k x k cubes over [0, size] (node coordinates jittered along each axis by the
/// monotone spacings xs, ys, zs of k + 1 entries each), every cube split into the 6 Kuhn tets.
/// Group of a tet: 1 + (cube index along x) % groups.
inline TetMesh grid_mesh(const std::vector<double>& xs, const std::vector<double>& ys,
                         const std::vector<double>& zs, int groups = 1) {
  TetMesh m;
  const int nx = static_cast<int>(xs.size()), ny = static_cast<int>(ys.size()),
            nz = static_cast<int>(zs.size());
  const auto id = [&](int i, int j, int k) { return i + nx * (j + ny * k); };
  for (int k = 0; k < nz; ++k)
    for (int j = 0; j < ny; ++j)
      for (int i = 0; i < nx; ++i)
        m.add_node(Vec3(xs[static_cast<std::size_t>(i)], ys[static_cast<std::size_t>(j)],
                        zs[static_cast<std::size_t>(k)]));
  const auto split = kuhn_tets();
  for (int k = 0; k + 1 < nz; ++k)
    for (int j = 0; j + 1 < ny; ++j)
      for (int i = 0; i + 1 < nx; ++i)
        for (const auto& t : split) {
          Tet ids{};
          for (int c = 0; c < 4; ++c) {
            const auto b = corner_bits(t[static_cast<std::size_t>(c)]);
            ids[static_cast<std::size_t>(c)] = id(i + b[0], j + b[1], k + b[2]);
          }
          m.add_tet(orient_positive(m.rest, ids), static_cast<std::uint16_t>(1 + i % groups));
        }
  return m;
}

/// k + 1 strictly increasing coordinates from 0 to `size`, with random (seeded) spacing.
inline std::vector<double> random_spacing(std::mt19937& rng, int k, double size) {
  std::uniform_real_distribution<double> u(0.3, 1.0);
  std::vector<double> w(static_cast<std::size_t>(k));
  double sum = 0.0;
  for (double& x : w) sum += (x = u(rng));
  std::vector<double> out{0.0};
  double acc = 0.0;
  for (int i = 0; i < k; ++i) {
    acc += w[static_cast<std::size_t>(i)];
    out.push_back(i + 1 == k ? size : size * acc / sum);
  }
  return out;
}

}  // namespace serosa::fixtures
