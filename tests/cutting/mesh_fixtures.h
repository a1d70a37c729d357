// Meshes for the cutting tests: single tets here; the structured grids are the shared
// test_meshes::kuhn_cube and kuhn_box (support/test_meshes.h).
#pragma once

#include <array>
#include <cstdint>
#include <random>
#include <utility>

#include "engine/tet_mesh.h"
#include "support/test_meshes.h"

namespace serosa::cutting::fixtures {

/// Appends tet (a, b, c, d), swapping c and d when its rest volume is negative.
inline void add_oriented(TetMesh& m, Tet t, std::uint16_t g) {
  if (signed_volume(m.rest[t[0]], m.rest[t[1]], m.rest[t[2]], m.rest[t[3]]) < 0.0)
    std::swap(t[2], t[3]);
  m.add_tet(t, g);
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
