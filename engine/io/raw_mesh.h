// RawMesh: what a reader found in a file, before validation (private to engine/io). Readers check
// syntax and counts; finish_mesh (mesh_validation.cpp) checks meaning: ids defined, in range and
// unique, finite coordinates, group range, flat and inverted tets. Every entry keeps the line it
// came from so that each error names the file and the line.
#pragma once

#include <array>
#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

#include "engine/io/mesh_io.h"
#include "engine/math.h"
#include "engine/tet_mesh.h"

namespace serosa::io {

struct RawMesh {
  std::string node_file;  ///< file the nodes came from (errors about nodes name it)
  std::string tet_file;   ///< file the tets came from (TetGen: the .ele; else node_file)
  // ---- per node (n), in file order ----
  std::vector<std::int64_t> node_id;       ///< (n) id as written in the file
  std::vector<Vec3> node_pos;              ///< (n) position, m
  std::vector<std::int64_t> node_id_line;  ///< (n) line of the id (1-based)
  std::vector<std::int64_t> node_line;     ///< (n) line of the coordinates (1-based)
  // ---- per tet (m), in file order ----
  std::vector<std::array<std::int64_t, 4>> tet_nodes;  ///< (m) node ids as written
  std::vector<std::int64_t> tet_group;                 ///< (m) group as written
  std::vector<std::int64_t> tet_line;                  ///< (m) line of the tet (1-based)
  std::vector<std::int64_t> tet_id;  ///< (m) its id as written (VTK: the cell's 0-based index)

  void add_node(std::int64_t id, const Vec3& p, std::int64_t id_line, std::int64_t line) {
    node_id.push_back(id);
    node_pos.push_back(p);
    node_id_line.push_back(id_line);
    node_line.push_back(line);
  }
  void add_tet(const std::array<std::int64_t, 4>& t, std::int64_t g, std::int64_t line,
               std::int64_t id) {
    tet_nodes.push_back(t);
    tet_group.push_back(g);
    tet_line.push_back(line);
    tet_id.push_back(id);
  }
};

/// Validates a raw mesh and builds the TetMesh (ids renumbered densely from 0 in file order,
/// x = rest, v = 0). Throws InputError on bad content; repairs inverted tets when asked and counts
/// them in report.repaired_inverted.
TetMesh finish_mesh(const RawMesh& raw, const MeshReadOptions& options, MeshReadReport& report);

/// Whole-file check before parsing: empty (or blank) text (InputError, line 0).
void check_text(std::string_view text, const std::string& name);
/// Binary data in a text format: a NUL byte (InputError at its line). Readers call it after their
/// header, so that a header announcing binary data gets its own, clearer error first.
void check_no_nul(std::string_view text, const std::string& name);

/// A reserve size for a count declared in a file: never more than the text could hold, so a
/// hostile count cannot allocate gigabytes.
/// @param declared    count from the file
/// @param text_size   bytes in the file
/// @param min_bytes   fewest bytes one entry can take
[[nodiscard]] inline std::size_t safe_reserve(std::int64_t declared, std::size_t text_size,
                                              std::size_t min_bytes) {
  if (declared <= 0) return 0;
  const std::size_t cap = text_size / (min_bytes > 0 ? min_bytes : 1) + 1;
  const auto d = static_cast<std::uint64_t>(declared);
  return d < cap ? static_cast<std::size_t>(d) : cap;
}

// The parsers (one file each). They fill report.format and report.skipped_elements (and
// report.group_names for Gmsh) and return what they read, unvalidated.
RawMesh parse_gmsh(std::string_view text, const std::string& name, MeshReadReport& report);
RawMesh parse_tetgen(std::string_view node_text, const std::string& node_name,
                     std::string_view ele_text, const std::string& ele_name,
                     MeshReadReport& report);
RawMesh parse_vtk(std::string_view text, const std::string& name, MeshReadReport& report);

}  // namespace serosa::io
