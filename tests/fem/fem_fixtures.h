// Helpers shared by the fem tests: clamping and jittering the structured grids
// (test_meshes::kuhn_bar, support/test_meshes.h), and small utilities.
#pragma once

#include <array>
#include <cstdint>
#include <random>
#include <vector>

#include "engine/tet_mesh.h"
#include "engine/topology_delta.h"
#include "support/test_meshes.h"

namespace serosa::fem::fixtures {

/// Moves interior nodes of a grid by up to `amount` x cell size in each direction (uniform).
/// Fixes every node on the x = 0 face (a clamped end).
inline void clamp_x0(TetMesh& m) {
  for (std::size_t i = 0; i < m.rest.size(); ++i) m.fixed[i] = m.rest[i].x() < 1e-12 ? 1 : 0;
}

/// A Kuhn bar (test_meshes::kuhn_bar, same arguments) with its node state, clamped at x = 0.
inline TetMesh clamped_bar(int nx, int ny, int nz, double hx, double hy, double hz) {
  TetMesh m = test_meshes::kuhn_bar(nx, ny, nz, hx, hy, hz);
  m.fill_node_state();
  clamp_x0(m);
  return m;
}

/// The delta that splits tet t of m into four at a new node with barycentric weights w of its
/// corners (the centroid by default; a tiny weight makes slivers).
inline TopologyDelta split_tet(const TetMesh& m, std::int32_t t,
                               const std::array<double, 4>& w = {0.25, 0.25, 0.25, 0.25}) {
  TopologyDelta d;
  d.removed_tets = {t};
  const Tet& n = m.tets[static_cast<std::size_t>(t)];
  NodeParent p;
  p.count = 4;
  p.nodes = n;
  p.weights = w;
  d.added_nodes.push_back(p);
  for (std::size_t i = 0; i < 4; ++i) {
    Tet s = n;
    s[i] = m.num_nodes();
    d.added_tets.push_back(s);
    d.added_groups.push_back(m.group[static_cast<std::size_t>(t)]);
  }
  return d;
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
