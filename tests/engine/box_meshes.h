// Test fixtures: one cube split into 5 or 6 tets, positively oriented, with known volume, surface
// area and boundary face count. Grids of cubes are the shared test_meshes::kuhn_lattice
// (support/test_meshes.h). Shared by tests/engine and tests/app (include "engine/box_meshes.h").
#pragma once

#include <array>
#include <cstdint>
#include <random>
#include <utility>
#include <vector>

#include "engine/math.h"
#include "engine/tet_mesh.h"
#include "support/test_meshes.h"

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

}  // namespace serosa::fixtures
