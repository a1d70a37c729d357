// Meshes and a brute-force reference shared by the surface tests.
#pragma once

#include <algorithm>
#include <array>
#include <cstdint>
#include <map>
#include <random>
#include <set>
#include <tuple>
#include <utility>
#include <vector>

#include "engine/tet_mesh.h"
#include "support/test_meshes.h"
#include "surface/face_key.h"
#include "surface/surface_mesh.h"

namespace serosa::surface::testing {

/// Swaps two nodes of each negatively oriented tet so that every tet is positive in rest space.
inline void orient_positive(TetMesh& m) {
  for (std::int32_t i = 0; i < m.num_tets(); ++i)
    if (m.rest_volume(i) < 0.0) std::swap(m.tets[i][2], m.tets[i][3]);
}

/// `tets` random positively oriented tets over `nodes` random nodes in [-1, 1]^3,
/// groups 1..ngroups. Faces may be shared by any number of tets (the reference handles that).
inline TetMesh random_mesh(std::mt19937& rng, int nodes, int tets, int ngroups) {
  TetMesh m;
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  for (int i = 0; i < nodes; ++i) m.add_node(Vec3(u(rng), u(rng), u(rng)));
  std::uniform_int_distribution<int> node(0, nodes - 1);
  std::uniform_int_distribution<int> group(1, ngroups);
  while (m.num_tets() < tets) {
    const Tet t{node(rng), node(rng), node(rng), node(rng)};
    const std::set<int> distinct(t.begin(), t.end());
    if (distinct.size() < 4) continue;
    const int i = m.add_tet(t, static_cast<std::uint16_t>(group(rng)));
    if (std::abs(m.rest_volume(i)) < 1e-6) {  // near-degenerate: drop
      m.tets.pop_back();
      m.group.pop_back();
    }
  }
  orient_positive(m);
  return m;
}

/// A face rotated so that its smallest id comes first (same orientation).
inline Tri canonical_rotation(Tri f) {
  while (f[0] > f[1] || f[0] > f[2]) f = Tri{f[1], f[2], f[0]};
  return f;
}

/// (group, oriented face up to rotation, owning tet): what two extractions must agree on.
using FaceRecord = std::tuple<std::uint16_t, Tri, std::int32_t>;

/// Brute force: every face of every tet in a std::map keyed by sorted ids; faces used once.
inline std::multiset<FaceRecord> reference_boundary(const TetMesh& m) {
  std::map<std::array<std::int32_t, 3>, std::vector<std::pair<std::int32_t, int>>> uses;
  for (std::int32_t t = 0; t < m.num_tets(); ++t)
    for (int l = 0; l < 4; ++l) {
      std::array<std::int32_t, 3> k{};
      outward_face(m.tets[t], l, k[0], k[1], k[2]);
      std::sort(k.begin(), k.end());
      uses[k].emplace_back(t, l);
    }
  std::multiset<FaceRecord> out;
  for (const auto& [key, list] : uses) {
    if (list.size() != 1) continue;
    const auto [t, l] = list.front();
    Tri f{};
    outward_face(m.tets[t], l, f[0], f[1], f[2]);
    out.emplace(m.group[t], canonical_rotation(f), t);
  }
  return out;
}

/// (oriented face up to rotation, group, face_cut): the cut flags two extractions must agree on.
using CutRecord = std::tuple<Tri, std::uint16_t, std::uint8_t>;

inline std::multiset<CutRecord> cut_records(const SurfaceMesh& s) {
  std::multiset<CutRecord> out;
  for (std::int32_t i = 0; i < s.num_faces(); ++i)
    out.emplace(canonical_rotation(s.faces[i]), s.face_group[i], s.face_cut[i]);
  return out;
}

inline std::multiset<FaceRecord> records(const SurfaceMesh& s) {
  std::multiset<FaceRecord> out;
  for (std::int32_t i = 0; i < s.num_faces(); ++i)
    out.emplace(s.face_group[i], canonical_rotation(s.faces[i]), s.face_tet[i]);
  return out;
}

}  // namespace serosa::surface::testing
