// Mesh files: read Gmsh 2.2 and 4.1 ASCII, TetGen .node/.ele and legacy VTK unstructured grids;
// write Gmsh 2.2 ASCII, VTU (ParaView) and OBJ (boundary surface); docs/ARCHITECTURE.md
// "External contracts".
//
// Every reader validates what it reads and throws InputError naming the file and the 1-based line
// on bad input: truncated file, wrong counts, node ids out of range or duplicated, NaN/inf
// coordinates, zero-volume or inverted tets, unknown version, binary where ASCII is expected.
// Element types other than 4-node tets are skipped. A tet's group is its Gmsh physical tag (VTK:
// a cell-data array named "group" or "gmsh:physical" when present, else 1; TetGen: the region
// attribute when present, else 1).
#pragma once

#include <cstdint>
#include <filesystem>
#include <iosfwd>
#include <map>
#include <span>
#include <string>
#include <vector>

#include "engine/math.h"
#include "engine/tet_mesh.h"

namespace serosa {

enum class MeshFormat { kAuto, kGmsh, kTetGen, kVtk };

struct MeshReadOptions {
  /// Inverted tets (negative rest volume) are an error unless this is set; then they are repaired
  /// by swapping their last two nodes and counted in MeshReadReport::repaired_inverted.
  bool repair_inverted = false;
  /// A tet whose |volume| is at most this fraction of (mean edge length)^3 is flat: always an
  /// error.
  double flat_tolerance = 1e-12;
};

struct MeshReadReport {
  std::string format;                      ///< "gmsh 2.2", "gmsh 4.1", "tetgen", "vtk 3.0" ...
  std::int64_t skipped_elements = 0;       ///< non-tet elements ignored
  std::int64_t repaired_inverted = 0;      ///< tets reordered (repair_inverted only)
  std::map<int, std::string> group_names;  ///< physical names when the file has them (Gmsh)
  std::vector<std::int64_t> tet_lines;     ///< (m) each tet's 1-based line in tet_file
  std::vector<std::int64_t> tet_ids;       ///< (m) each tet's id as written (VTK: cell index)
  std::string tet_file;                    ///< the file the tets came from (TetGen: the .ele)
};

/// Reads a mesh file. kAuto picks the format from the extension: .msh -> Gmsh (version from its
/// header), .node or .ele -> TetGen (the sibling file with the other extension is read too),
/// .vtk -> legacy VTK. Node ids are renumbered densely from 0 in file order. x = rest, v = 0.
TetMesh read_mesh(const std::filesystem::path& path, const MeshReadOptions& options = {},
                  MeshReadReport* report = nullptr, MeshFormat format = MeshFormat::kAuto);

/// Same readers on in-memory text (fuzzing, tests). `name` stands for the file in errors.
/// kTetGen takes `text` as the .node file and `ele_text` as the .ele file.
TetMesh read_mesh_text(const std::string& text, MeshFormat format, const std::string& name,
                       const MeshReadOptions& options = {}, MeshReadReport* report = nullptr,
                       const std::string& ele_text = {});

/// Gmsh 2.2 ASCII: nodes at rest positions (or current when `current` is set), tets as element
/// type 4 with the group as physical tag (and as elementary tag). group_names -> $PhysicalNames.
void write_gmsh22(const std::filesystem::path& path, const TetMesh& mesh, bool current = false,
                  const std::map<int, std::string>& group_names = {});

/// VTU (XML UnstructuredGrid, ASCII) that ParaView opens: points (current positions), tets (VTK
/// type 10), cell data "group" (int) and point data "rest" (m) and "velocity" (m/s).
void write_vtu(const std::filesystem::path& path, const TetMesh& mesh);

/// OBJ of a triangle surface over the mesh's nodes: every node is written as `v` (so face ids are
/// node ids + 1), faces grouped by `face_group` as `g NAME` blocks, each face wound as given
/// (callers pass outward-oriented faces). group_names maps a group to its OBJ group name
/// (default "group_<id>").
/// @param positions (n) node positions, m
/// @param faces     (f) node ids per face
/// @param face_group (f) group of each face
void write_obj(const std::filesystem::path& path, std::span<const Vec3> positions,
               std::span<const Tri> faces, std::span<const std::uint16_t> face_group,
               const std::map<int, std::string>& group_names = {});

}  // namespace serosa
