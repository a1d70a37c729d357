// Shared post-read validation of every mesh reader: ids defined, in range and unique; finite
// coordinates; groups that fit a uint16; no tet that repeats a node, is flat or is inverted
// (inverted tets are repaired on request).
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <limits>
#include <string>
#include <unordered_map>

#include "engine/input_error.h"
#include "engine/io/raw_mesh.h"

namespace serosa::io {
namespace {

std::string num(double v) {
  char buf[32];
  const int n = std::snprintf(buf, sizeof buf, "%.6g", v);
  return std::string(buf, static_cast<std::size_t>(n > 0 ? n : 0));
}

// Maps node ids as written to dense indices: a table when the ids are compact (the usual case),
// else a hash map.
class IdMap {
 public:
  explicit IdMap(const RawMesh& raw) : m_raw(raw) {
    const auto& ids = raw.node_id;
    const auto [lo, hi] = std::minmax_element(ids.begin(), ids.end());
    m_min = *lo;
    m_max = *hi;
    const auto n = static_cast<std::uint64_t>(ids.size());
    // hi - lo may overflow int64 for hostile ids: compare in unsigned arithmetic.
    const std::uint64_t span =
        static_cast<std::uint64_t>(m_max) - static_cast<std::uint64_t>(m_min);
    m_dense = span < 4 * n + 1024;
    if (m_dense) {
      m_table.assign(static_cast<std::size_t>(span) + 1, -1);
    } else {
      m_hash.reserve(ids.size());
    }
    for (std::size_t i = 0; i < ids.size(); ++i) insert(ids[i], static_cast<std::int32_t>(i));
  }

  /// Dense index of id, or -1.
  [[nodiscard]] std::int32_t find(std::int64_t id) const {
    if (id < m_min || id > m_max) return -1;
    if (m_dense) return m_table[static_cast<std::size_t>(id - m_min)];
    const auto it = m_hash.find(id);
    return it == m_hash.end() ? -1 : it->second;
  }
  [[nodiscard]] std::int64_t min() const { return m_min; }
  [[nodiscard]] std::int64_t max() const { return m_max; }

 private:
  void insert(std::int64_t id, std::int32_t index) {
    std::int32_t* slot = nullptr;
    if (m_dense) {
      slot = &m_table[static_cast<std::size_t>(id - m_min)];
    } else {
      slot = &m_hash.try_emplace(id, -1).first->second;
    }
    if (*slot >= 0) {
      const auto first = static_cast<std::size_t>(*slot);
      throw InputError(m_raw.node_file, m_raw.node_id_line[static_cast<std::size_t>(index)],
                       "node id " + std::to_string(id) + " defined twice (first at line " +
                           std::to_string(m_raw.node_id_line[first]) + ")",
                       "unique node ids");
    }
    *slot = index;
  }

  const RawMesh& m_raw;
  std::int64_t m_min = 0;
  std::int64_t m_max = 0;
  bool m_dense = true;
  std::vector<std::int32_t> m_table;
  std::unordered_map<std::int64_t, std::int32_t> m_hash;
};

}  // namespace

void check_text(std::string_view text, const std::string& name) {
  if (text.find_first_not_of(" \t\r\n\v\f") == std::string_view::npos) {
    throw InputError(name, 0, "empty file", "a mesh");
  }
}

void check_no_nul(std::string_view text, const std::string& name) {
  const void* nul = std::memchr(text.data(), '\0', text.size());
  if (nul != nullptr) {
    const auto at = static_cast<std::size_t>(static_cast<const char*>(nul) - text.data());
    const auto line =
        1 + std::count(text.begin(), text.begin() + static_cast<std::ptrdiff_t>(at), '\n');
    throw InputError(name, line, "binary data (a NUL byte) in a text mesh file", "ASCII text");
  }
}

TetMesh finish_mesh(const RawMesh& raw, const MeshReadOptions& options, MeshReadReport& report) {
  report.tet_lines = raw.tet_line;
  report.tet_ids = raw.tet_id;
  report.tet_file = raw.tet_file;
  const std::size_t n = raw.node_id.size();
  const std::size_t m = raw.tet_nodes.size();
  constexpr auto kMaxCount = static_cast<std::size_t>(std::numeric_limits<std::int32_t>::max());
  if (n == 0) throw InputError(raw.node_file, 0, "no nodes in file", "a mesh with nodes");
  if (m == 0) {
    throw InputError(raw.tet_file, 0, "no 4-node tetrahedra in file", "a tetrahedral volume mesh");
  }
  if (n > kMaxCount) throw InputError(raw.node_file, 0, "too many nodes", "at most 2^31-1");
  if (m > kMaxCount) throw InputError(raw.tet_file, 0, "too many tets", "at most 2^31-1");

  // Nodes: unique ids, finite coordinates.
  const IdMap ids(raw);
  for (std::size_t i = 0; i < n; ++i) {
    if (!raw.node_pos[i].allFinite()) {
      throw InputError(
          raw.node_file, raw.node_line[i],
          "coordinate of node " + std::to_string(raw.node_id[i]) + " is NaN or infinite",
          "finite numbers");
    }
  }

  TetMesh mesh;
  mesh.rest = raw.node_pos;
  mesh.tets.resize(m);
  mesh.group.resize(m);
  for (std::size_t k = 0; k < m; ++k) {
    const std::int64_t line = raw.tet_line[k];
    auto fail = [&](const std::string& message, const std::string& expected) {
      throw InputError(raw.tet_file, line, message, expected);
    };
    // Node ids defined and distinct.
    Tet t{};
    for (int j = 0; j < 4; ++j) {
      const std::int64_t id = raw.tet_nodes[k][static_cast<std::size_t>(j)];
      const std::int32_t idx = ids.find(id);
      if (idx < 0) {
        fail("tet refers to node id " + std::to_string(id) + ", which is not defined",
             "a node id defined in the node list (ids " + std::to_string(ids.min()) + ".." +
                 std::to_string(ids.max()) + ")");
      }
      for (int i = 0; i < j; ++i) {
        if (t[static_cast<std::size_t>(i)] == idx) {
          fail("tet uses node id " + std::to_string(id) + " twice", "four distinct nodes");
        }
      }
      t[static_cast<std::size_t>(j)] = idx;
    }
    // Group fits a uint16.
    const std::int64_t g = raw.tet_group[k];
    if (g < 0 || g > std::numeric_limits<std::uint16_t>::max()) {
      fail("group " + std::to_string(g) + " out of range", "a group id in 0..65535");
    }
    // Flat and inverted tets.
    const Vec3& a = mesh.rest[static_cast<std::size_t>(t[0])];
    const Vec3& b = mesh.rest[static_cast<std::size_t>(t[1])];
    const Vec3& c = mesh.rest[static_cast<std::size_t>(t[2])];
    const Vec3& d = mesh.rest[static_cast<std::size_t>(t[3])];
    const double vol = signed_volume(a, b, c, d);
    const double edge = ((b - a).norm() + (c - a).norm() + (d - a).norm() + (c - b).norm() +
                         (d - b).norm() + (d - c).norm()) /
                        6.0;
    if (!std::isfinite(vol) || !std::isfinite(edge)) {
      fail("tet volume is not finite (coordinates too large)", "coordinates below ~1e100 m");
    }
    const double flat = options.flat_tolerance * edge * edge * edge;
    if (!(std::abs(vol) > flat)) {
      fail("zero-volume (flat) tet: volume " + num(vol) + " m^3, mean edge " + num(edge) + " m",
           "|volume| above flat_tolerance * (mean edge)^3 = " + num(flat) + " m^3");
    }
    if (vol < 0.0) {
      if (!options.repair_inverted) {
        fail("inverted tet (negative volume " + num(vol) + " m^3)",
             "positive orientation (`serosa check --repair-inverted` swaps two nodes)");
      }
      std::swap(t[2], t[3]);
      ++report.repaired_inverted;
    }
    mesh.tets[k] = t;
    mesh.group[k] = static_cast<std::uint16_t>(g);
  }
  mesh.fill_node_state();
  return mesh;
}

}  // namespace serosa::io
