// write_gmsh22: Gmsh 2.2 ASCII. Nodes are numbered from 1 in mesh order, tets are element type 4
// with two tags (physical = elementary = group), group names go to $PhysicalNames (dimension 3).
#include <cmath>
#include <stdexcept>
#include <string>

#include "engine/io/mesh_io.h"
#include "engine/io/text_format.h"

namespace serosa {

void write_gmsh22(const std::filesystem::path& path, const TetMesh& mesh, bool current,
                  const std::map<int, std::string>& group_names) {
  const std::vector<Vec3>& pos = current ? mesh.x : mesh.rest;
  const std::string where = path.string() + ": ";
  if (pos.size() != mesh.rest.size()) {
    throw std::invalid_argument(where + "mesh.x has " + std::to_string(pos.size()) +
                                " entries for " + std::to_string(mesh.rest.size()) + " nodes");
  }
  if (mesh.group.size() != mesh.tets.size()) {
    throw std::invalid_argument(where + "mesh.group and mesh.tets differ in size");
  }
  const auto n = static_cast<std::int64_t>(pos.size());

  std::string out;
  out.reserve(64 + pos.size() * 64 + mesh.tets.size() * 48);
  out.append("$MeshFormat\n2.2 0 8\n$EndMeshFormat\n");
  if (!group_names.empty()) {
    out.append("$PhysicalNames\n");
    io::append_int(out, static_cast<std::int64_t>(group_names.size()));
    out.push_back('\n');
    for (const auto& [tag, name] : group_names) {
      out.append("3 ");
      io::append_int(out, tag);
      out.append(" \"");
      for (const char c : name) out.push_back(c == '"' ? '\'' : (c == '\n' || c == '\r' ? ' ' : c));
      out.append("\"\n");
    }
    out.append("$EndPhysicalNames\n");
  }

  out.append("$Nodes\n");
  io::append_int(out, n);
  out.push_back('\n');
  for (std::int64_t i = 0; i < n; ++i) {
    const Vec3& p = pos[static_cast<std::size_t>(i)];
    if (!p.allFinite()) {
      throw std::invalid_argument(where + "node " + std::to_string(i) +
                                  " has a NaN or infinite coordinate");
    }
    io::append_int(out, i + 1);
    for (int k = 0; k < 3; ++k) {
      out.push_back(' ');
      io::append_double(out, p[k]);
    }
    out.push_back('\n');
  }
  out.append("$EndNodes\n$Elements\n");
  io::append_int(out, static_cast<std::int64_t>(mesh.tets.size()));
  out.push_back('\n');
  for (std::size_t k = 0; k < mesh.tets.size(); ++k) {
    io::append_int(out, static_cast<std::int64_t>(k) + 1);
    out.append(" 4 2 ");
    io::append_int(out, mesh.group[k]);
    out.push_back(' ');
    io::append_int(out, mesh.group[k]);
    for (const std::int32_t id : mesh.tets[k]) {
      if (id < 0 || id >= n) {
        throw std::invalid_argument(where + "tet " + std::to_string(k) + " refers to node " +
                                    std::to_string(id) + " of " + std::to_string(n));
      }
      out.push_back(' ');
      io::append_int(out, static_cast<std::int64_t>(id) + 1);
    }
    out.push_back('\n');
  }
  out.append("$EndElements\n");
  io::write_text_file(path, out);
}

}  // namespace serosa
