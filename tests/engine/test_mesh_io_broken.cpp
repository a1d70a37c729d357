// The broken-file corpus (tests/data/broken): every file must be refused with an InputError that
// names the file and, except for whole-file errors (files named file_*), the 1-based line. Each
// file has an expectation below; a new file without one fails the test.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <map>
#include <string>
#include <vector>

#include "engine/input_error.h"
#include "engine/io/mesh_io.h"
#include "support/test_paths.h"
#include "test_mesh_io_util.h"

namespace serosa {
namespace {

namespace fs = std::filesystem;

struct Expect {
  std::string names;  ///< file name the error must name (a TetGen pair may blame its sibling)
  std::int64_t line;  ///< 1-based line, 0 for whole-file errors
  std::string says;   ///< part of the message
};

const std::map<std::string, Expect>& expectations() {
  static const std::map<std::string, Expect> table = {
      {"file_blank.vtk", {"file_blank.vtk", 0, "empty file"}},
      {"file_empty.msh", {"file_empty.msh", 0, "empty file"}},
      {"file_gmsh22_no_nodes_section.msh", {"file_gmsh22_no_nodes_section.msh", 0, "no $Nodes"}},
      {"file_gmsh22_no_tets.msh", {"file_gmsh22_no_tets.msh", 0, "no 4-node tetrahedra"}},
      {"file_tetgen_missing_ele.node", {"file_tetgen_missing_ele.ele", 0, "cannot open file"}},
      {"file_unknown_extension.stl",
       {"file_unknown_extension.stl", 0, "unknown mesh file extension"}},
      {"garbage_text.msh", {"garbage_text.msh", 1, "not a Gmsh mesh"}},
      {"gmsh22_binary_file_type_1.msh", {"gmsh22_binary_file_type_1.msh", 2, "binary Gmsh file"}},
      {"gmsh22_duplicate_node_id.msh", {"gmsh22_duplicate_node_id.msh", 9, "defined twice"}},
      {"gmsh22_fewer_elements_than_declared.msh",
       {"gmsh22_fewer_elements_than_declared.msh", 17, "after only 3 elements (4 declared)"}},
      {"gmsh22_fewer_nodes_than_declared.msh",
       {"gmsh22_fewer_nodes_than_declared.msh", 11, "after only 5 nodes (6 declared)"}},
      {"gmsh22_flat_tet.msh", {"gmsh22_flat_tet.msh", 16, "flat"}},
      {"gmsh22_garbage_coordinate.msh",
       {"gmsh22_garbage_coordinate.msh", 7, "'abc' is not a number"}},
      {"gmsh22_group_out_of_range.msh",
       {"gmsh22_group_out_of_range.msh", 15, "group 70000 out of range"}},
      {"gmsh22_inf_coordinate.msh", {"gmsh22_inf_coordinate.msh", 7, "NaN or infinite"}},
      {"gmsh22_inverted_tet.msh", {"gmsh22_inverted_tet.msh", 16, "inverted tet"}},
      {"gmsh22_missing_endmeshformat.msh",
       {"gmsh22_missing_endmeshformat.msh", 3, "$EndMeshFormat"}},
      {"gmsh22_more_elements_than_declared.msh",
       {"gmsh22_more_elements_than_declared.msh", 16, "more elements than the 2 declared"}},
      {"gmsh22_more_nodes_than_declared.msh",
       {"gmsh22_more_nodes_than_declared.msh", 10, "more nodes than the 4 declared"}},
      {"gmsh22_nan_coordinate.msh", {"gmsh22_nan_coordinate.msh", 8, "NaN or infinite"}},
      {"gmsh22_node_line_missing_z.msh",
       {"gmsh22_node_line_missing_z.msh", 8, "line ends too early"}},
      {"gmsh22_nul_byte_in_nodes.msh", {"gmsh22_nul_byte_in_nodes.msh", 8, "binary data"}},
      {"gmsh22_tet_line_extra_node.msh", {"gmsh22_tet_line_extra_node.msh", 15, "unexpected '5'"}},
      {"gmsh22_tet_repeats_node.msh", {"gmsh22_tet_repeats_node.msh", 15, "node id 2 twice"}},
      {"gmsh22_truncated_in_nodes.msh",
       {"gmsh22_truncated_in_nodes.msh", 8, "unexpected end of file"}},
      {"gmsh22_unclosed_section.msh", {"gmsh22_unclosed_section.msh", 18, "never closed"}},
      {"gmsh22_undefined_node_id.msh",
       {"gmsh22_undefined_node_id.msh", 16, "node id 9, which is not defined"}},
      {"gmsh41_duplicate_node_tag.msh", {"gmsh41_duplicate_node_tag.msh", 17, "defined twice"}},
      {"gmsh41_more_elements_than_declared.msh",
       {"gmsh41_more_elements_than_declared.msh", 30, "more elements or element blocks"}},
      {"gmsh41_node_blocks_fewer_than_header.msh",
       {"gmsh41_node_blocks_fewer_than_header.msh", 13, "hold 5 nodes but the header declares 6"}},
      {"gmsh41_physical_name_unquoted.msh", {"gmsh41_physical_name_unquoted.msh", 6, "not quoted"}},
      {"gmsh41_tet_node_undefined.msh", {"gmsh41_tet_node_undefined.msh", 30, "not defined"}},
      {"gmsh41_truncated_entities.msh",
       {"gmsh41_truncated_entities.msh", 11, "after only 1 volume entities (2 declared)"}},
      {"gmsh41_truncated_in_elements.msh",
       {"gmsh41_truncated_in_elements.msh", 29, "unexpected end of file"}},
      {"gmsh_unknown_version_3_0.msh",
       {"gmsh_unknown_version_3_0.msh", 2, "unsupported Gmsh format version '3.0'"}},
      {"random_bytes.vtk", {"random_bytes.vtk", 1, "not a legacy VTK file"}},
      {"tetgen_dimension_2.node", {"tetgen_dimension_2.node", 2, "dimension 2"}},
      {"tetgen_fewer_points_than_declared.node",
       {"tetgen_fewer_points_than_declared.node", 7, "unexpected end of file"}},
      {"tetgen_more_tets_than_declared.node",
       {"tetgen_more_tets_than_declared.ele", 3, "more tets than the 1 declared"}},
      {"tetgen_node_id_out_of_range.node",
       {"tetgen_node_id_out_of_range.ele", 3, "node id 6, which is not defined"}},
      {"tetgen_region_not_integer.node",
       {"tetgen_region_not_integer.ele", 2, "'1.5' is not an integer"}},
      {"vtk_binary.vtk", {"vtk_binary.vtk", 3, "binary VTK file"}},
      {"vtk_cell_point_count_overflows.vtk",
       {"vtk_cell_point_count_overflows.vtk", 10, "cell list longer than the size 10 declared"}},
      {"vtk_cell_types_count_mismatch.vtk",
       {"vtk_cell_types_count_mismatch.vtk", 12, "CELL_TYPES declares 3 cells"}},
      {"vtk_cells_size_mismatch.vtk",
       {"vtk_cells_size_mismatch.vtk", 9, "declares size 11 but the cells use 10"}},
      {"vtk_fewer_points_than_declared.vtk",
       {"vtk_fewer_points_than_declared.vtk", 9, "'CELLS' where data was expected"}},
      {"vtk_group_not_integer.vtk",
       {"vtk_group_not_integer.vtk", 19, "group value 4.5 is not an integer"}},
      {"vtk_nan_point.vtk", {"vtk_nan_point.vtk", 8, "NaN or infinite"}},
      {"vtk_point_index_out_of_range.vtk",
       {"vtk_point_index_out_of_range.vtk", 11, "node id 5, which is not defined"}},
      {"vtk_structured_points.vtk",
       {"vtk_structured_points.vtk", 4, "'STRUCTURED_POINTS' is not supported"}},
      {"vtk_tetra_with_5_points.vtk", {"vtk_tetra_with_5_points.vtk", 11, "with 5 points"}},
      {"vtk_truncated_in_cells.vtk", {"vtk_truncated_in_cells.vtk", 10, "unexpected end of file"}},
      {"vtk_unknown_version_6_0.vtk",
       {"vtk_unknown_version_6_0.vtk", 1, "unsupported VTK file version '6.0'"}},
  };
  return table;
}

fs::path broken_dir() { return fs::path(::serosa::test_paths::test_data()) / "broken"; }

std::vector<fs::path> corpus() {
  std::vector<fs::path> files;
  for (const auto& e : fs::directory_iterator(broken_dir())) {
    if (e.is_regular_file()) files.push_back(e.path());
  }
  std::sort(files.begin(), files.end());
  return files;
}

// A TetGen .ele file is read as its pair: it shares the expectation of the .node beside it.
std::string expectation_key(const fs::path& p) {
  if (p.extension() == ".ele") {
    fs::path node = p;
    node.replace_extension(".node");
    if (fs::exists(node)) return node.filename().string();
  }
  return p.filename().string();
}

TEST(MeshIoBroken, CorpusHasAtLeastTwentyFiles) { EXPECT_GE(corpus().size(), 20U); }

TEST(MeshIoBroken, EveryFileThrowsInputErrorNamingFileAndLine) {
  for (const fs::path& p : corpus()) {
    const std::string name = p.filename().string();
    SCOPED_TRACE(name);
    const auto it = expectations().find(expectation_key(p));
    if (it == expectations().end()) {
      ADD_FAILURE() << "no expectation for " << name << ": add one to the table";
      continue;
    }
    const Expect& x = it->second;
    try {
      (void)read_mesh(p);
      ADD_FAILURE() << "read without error";
    } catch (const InputError& e) {
      const std::string what = e.what();
      EXPECT_EQ(fs::path(e.file()).filename().string(), x.names) << what;
      EXPECT_NE(what.find(x.names), std::string::npos) << what;
      EXPECT_EQ(e.line(), x.line) << what;
      EXPECT_NE(what.find(x.says), std::string::npos) << what;
      EXPECT_FALSE(e.expected().empty()) << what;
      // Whole-file errors (line 0) exactly for the files named so.
      EXPECT_EQ(e.line() == 0, name.rfind("file_", 0) == 0) << what;
      if (e.line() > 0) {
        EXPECT_NE(what.find(x.names + ":" + std::to_string(x.line) + ": "), std::string::npos)
            << what;
      }
    }
  }
}

TEST(MeshIoBroken, EveryExpectationHasItsFile) {
  for (const auto& [name, x] : expectations()) {
    EXPECT_TRUE(fs::exists(broken_dir() / name)) << name;
  }
}

TEST(MeshIoBroken, MissingFileIsAWholeFileError) {
  test::ScratchDir dir;
  for (const char* name : {"absent.msh", "absent.vtk", "absent.node", "absent.ele"}) {
    try {
      (void)read_mesh(dir / name);
      ADD_FAILURE() << name;
    } catch (const InputError& e) {
      EXPECT_EQ(e.line(), 0);
      EXPECT_NE(std::string(e.what()).find("absent."), std::string::npos);
      EXPECT_NE(std::string(e.what()).find("cannot open"), std::string::npos);
    }
  }
}

TEST(MeshIoBroken, DirectoryIsAnError) {
  test::ScratchDir dir;
  std::filesystem::create_directory(dir / "d.msh");
  EXPECT_THROW((void)read_mesh(dir / "d.msh"), InputError);
}

TEST(MeshIoBroken, InvertedTetIsRepairedOnRequestAndCounted) {
  MeshReadOptions opt;
  opt.repair_inverted = true;
  MeshReadReport report;
  const TetMesh m = read_mesh(broken_dir() / "gmsh22_inverted_tet.msh", opt, &report);
  EXPECT_EQ(report.repaired_inverted, 1);
  test::expect_mesh_invariants(m);
  // The repaired tet keeps its nodes, with the last two swapped.
  EXPECT_EQ(m.tets[1], (Tet{1, 3, 4, 2}));
}

TEST(MeshIoBroken, RepairDoesNotExcuseFlatTets) {
  MeshReadOptions opt;
  opt.repair_inverted = true;
  opt.flat_tolerance = 0.0;  // even with no tolerance, an exactly flat tet is refused
  EXPECT_THROW((void)read_mesh(broken_dir() / "gmsh22_flat_tet.msh", opt), InputError);
}

TEST(MeshIoBroken, FlatToleranceScalesWithEdgeLength) {
  // A sliver of height h (times scale): flat exactly when its volume is below the tolerance times
  // the cube of its mean edge, whatever the scale.
  for (const double h : {1e-3, 1e-6, 1e-9}) {
    for (const double scale : {1e-3, 1.0, 1e3}) {
      std::string text = "$MeshFormat\n2.2 0 8\n$EndMeshFormat\n$Nodes\n4\n";
      auto node = [&](int id, double x, double y, double z) {
        char buf[128];
        std::snprintf(buf, sizeof buf, "%d %.17g %.17g %.17g\n", id, x * scale, y * scale,
                      z * scale);
        text += buf;
      };
      node(1, 0, 0, 0);
      node(2, 1, 0, 0);
      node(3, 0, 1, 0);
      node(4, 0.3, 0.3, h);
      text += "$EndNodes\n$Elements\n1\n1 4 2 1 1 1 2 3 4\n$EndElements\n";
      MeshReadOptions opt;
      opt.flat_tolerance = 1e-7;  // volume h/6 vs tolerance * (mean edge ~0.9)^3 ~ 7e-8
      const bool flat = h < 1e-6;
      SCOPED_TRACE("h=" + std::to_string(h) + " scale=" + std::to_string(scale));
      if (flat) {
        EXPECT_THROW((void)read_mesh_text(text, MeshFormat::kGmsh, "sliver.msh", opt), InputError);
      } else {
        EXPECT_NO_THROW((void)read_mesh_text(text, MeshFormat::kGmsh, "sliver.msh", opt));
      }
    }
  }
}

}  // namespace
}  // namespace serosa
