// Helpers shared by the mesh I/O tests: a scratch directory, random valid meshes, mesh equality.
#pragma once

#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <random>
#include <sstream>
#include <string>

#include "engine/math.h"
#include "engine/tet_mesh.h"

namespace serosa::test {

/// A fresh directory under the system temp dir, removed with everything in it at scope end.
class ScratchDir {
 public:
  ScratchDir() {
    std::random_device rd;
    const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
    std::string name = "serosa_meshio_";
    if (info != nullptr) name += std::string(info->test_suite_name()) + "_" + info->name() + "_";
    for (char& c : name) {
      if (c == '/') c = '_';
    }
    m_path = std::filesystem::temp_directory_path() / (name + std::to_string(rd()));
    std::filesystem::create_directories(m_path);
  }
  ~ScratchDir() {
    std::error_code ec;
    std::filesystem::remove_all(m_path, ec);
  }
  ScratchDir(const ScratchDir&) = delete;
  ScratchDir& operator=(const ScratchDir&) = delete;
  [[nodiscard]] std::filesystem::path operator/(const std::string& file) const {
    return m_path / file;
  }

 private:
  std::filesystem::path m_path;
};

/// prefix + i + ext, appended piece by piece (g++ 12 reports a false -Wrestrict on operator+
/// chains at -O3).
inline std::string numbered(const char* prefix, int i, const char* ext) {
  std::string s = prefix;
  s += std::to_string(i);
  s += ext;
  return s;
}

inline std::string slurp(const std::filesystem::path& p) {
  std::ifstream in(p, std::ios::binary);
  std::stringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

inline void spit(const std::filesystem::path& p, const std::string& text) {
  std::ofstream out(p, std::ios::binary);
  out << text;
}

/// A random valid mesh: `nodes` nodes at a random scale and offset (some may stay unused), `tets`
/// positively oriented, non-flat tets on random distinct nodes, random groups over all of uint16.
inline TetMesh random_valid_mesh(std::mt19937& rng, int nodes, int tets) {
  TetMesh m;
  std::uniform_real_distribution<double> unit(-1.0, 1.0);
  std::uniform_real_distribution<double> expo(-6.0, 3.0);
  const double scale = std::pow(10.0, expo(rng));
  const Vec3 offset(unit(rng) * 100.0 * scale, unit(rng) * scale, unit(rng) * 1e3);
  for (int i = 0; i < nodes; ++i) {
    m.add_node(offset + scale * Vec3(unit(rng), unit(rng), unit(rng)));
  }
  std::uniform_int_distribution<int> node(0, nodes - 1);
  std::uniform_int_distribution<int> group(0, 65535);
  while (m.num_tets() < tets) {
    Tet t{node(rng), node(rng), node(rng), node(rng)};
    if (t[0] == t[1] || t[0] == t[2] || t[0] == t[3] || t[1] == t[2] || t[1] == t[3] ||
        t[2] == t[3]) {
      continue;
    }
    const auto p = [&](int k) {
      return m.rest[static_cast<std::size_t>(t[static_cast<std::size_t>(k)])];
    };
    double v = signed_volume(p(0), p(1), p(2), p(3));
    if (std::abs(v) < 1e-3 * scale * scale * scale) continue;  // far from flat
    if (v < 0) std::swap(t[2], t[3]);
    m.add_tet(t, static_cast<std::uint16_t>(group(rng)));
  }
  return m;
}

/// Exact equality of positions (bit for bit), tets and groups.
inline void expect_same_mesh(const TetMesh& a, const TetMesh& b) {
  ASSERT_EQ(a.num_nodes(), b.num_nodes());
  ASSERT_EQ(a.num_tets(), b.num_tets());
  for (std::size_t i = 0; i < a.rest.size(); ++i) {
    ASSERT_EQ(a.rest[i], b.rest[i]) << "node " << i;
  }
  for (std::size_t k = 0; k < a.tets.size(); ++k) {
    ASSERT_EQ(a.tets[k], b.tets[k]) << "tet " << k;
    ASSERT_EQ(a.group[k], b.group[k]) << "tet " << k;
  }
}

/// What every successfully read mesh must satisfy.
inline void expect_mesh_invariants(const TetMesh& m) {
  const auto n = static_cast<std::size_t>(m.num_nodes());
  ASSERT_EQ(m.x.size(), n);
  ASSERT_EQ(m.v.size(), n);
  ASSERT_EQ(m.mass.size(), n);
  ASSERT_EQ(m.fixed.size(), n);
  ASSERT_EQ(m.group.size(), m.tets.size());
  ASSERT_GT(m.num_tets(), 0);
  for (std::size_t i = 0; i < n; ++i) {
    ASSERT_TRUE(m.rest[i].allFinite());
    ASSERT_EQ(m.x[i], m.rest[i]);
    ASSERT_EQ(m.v[i], Vec3::Zero());
  }
  for (std::int32_t k = 0; k < m.num_tets(); ++k) {
    for (const std::int32_t id : m.tets[static_cast<std::size_t>(k)]) {
      ASSERT_GE(id, 0);
      ASSERT_LT(id, m.num_nodes());
    }
    ASSERT_GT(m.rest_volume(k), 0.0) << "tet " << k;
  }
}

}  // namespace serosa::test
