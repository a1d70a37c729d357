// write_obj: a triangle surface as Wavefront OBJ. Every node is a `v` line (face ids = node ids +
// 1); faces are gathered per group, in increasing group order and in their given order within a
// group, each group under one `g NAME` line.
#include <algorithm>
#include <cctype>
#include <stdexcept>
#include <string>
#include <vector>

#include "engine/io/mesh_io.h"
#include "engine/io/text_format.h"

namespace serosa {
namespace {

// An OBJ group name is one word: whitespace becomes '_'.
std::string obj_name(const std::string& name) {
  std::string s = name;
  for (char& c : s) {
    if (std::isspace(static_cast<unsigned char>(c)) != 0) c = '_';
  }
  return s.empty() ? std::string("_") : s;
}

}  // namespace

void write_obj(const std::filesystem::path& path, std::span<const Vec3> positions,
               std::span<const Tri> faces, std::span<const std::uint16_t> face_group,
               const std::map<int, std::string>& group_names) {
  const std::string where = path.string() + ": ";
  if (faces.size() != face_group.size()) {
    throw std::invalid_argument(where + std::to_string(faces.size()) + " faces but " +
                                std::to_string(face_group.size()) + " face groups");
  }
  const auto n = static_cast<std::int64_t>(positions.size());
  std::string out;
  out.reserve(64 + positions.size() * 64 + faces.size() * 32);
  out.append("# Serosa surface: ");
  io::append_int(out, n);
  out.append(" vertices, ");
  io::append_int(out, static_cast<std::int64_t>(faces.size()));
  out.append(" faces\n");
  for (const Vec3& p : positions) {
    out.push_back('v');
    for (int k = 0; k < 3; ++k) {
      out.push_back(' ');
      io::append_double(out, p[k]);
    }
    out.push_back('\n');
  }

  // Faces ordered by group, stable within a group.
  std::vector<std::size_t> order(faces.size());
  for (std::size_t i = 0; i < order.size(); ++i) order[i] = i;
  std::stable_sort(order.begin(), order.end(),
                   [&](std::size_t a, std::size_t b) { return face_group[a] < face_group[b]; });
  bool first = true;
  std::uint16_t current = 0;
  for (const std::size_t f : order) {
    const std::uint16_t g = face_group[f];
    if (first || g != current) {
      const auto it = group_names.find(g);
      out.append("g ");
      out.append(it != group_names.end() ? obj_name(it->second) : "group_" + std::to_string(g));
      out.push_back('\n');
      current = g;
      first = false;
    }
    out.push_back('f');
    for (const std::int32_t id : faces[f]) {
      if (id < 0 || id >= n) {
        throw std::invalid_argument(where + "face " + std::to_string(f) + " refers to node " +
                                    std::to_string(id) + " of " + std::to_string(n));
      }
      out.push_back(' ');
      io::append_int(out, static_cast<std::int64_t>(id) + 1);
    }
    out.push_back('\n');
  }
  io::write_text_file(path, out);
}

}  // namespace serosa
