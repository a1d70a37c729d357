// Mesh readers on valid input: every sample format of the same box mesh reads to the same TetMesh;
// groups, names, skipped elements, id renumbering and the less common layouts of each format.
#include <gtest/gtest.h>

#include <filesystem>
#include <map>
#include <sstream>
#include <string>

#include "engine/input_error.h"
#include "engine/io/mesh_io.h"
#include "support/test_paths.h"
#include "test_mesh_io_util.h"

namespace serosa {
namespace {

namespace fs = std::filesystem;

fs::path sample(const std::string& name) {
  return fs::path(::serosa::test_paths::test_data()) / "meshes" / name;
}

// Total and per-group volume of a mesh, m^3.
std::map<int, double> group_volumes(const TetMesh& m) {
  std::map<int, double> v;
  for (std::int32_t k = 0; k < m.num_tets(); ++k)
    v[m.group[static_cast<std::size_t>(k)]] += m.rest_volume(k);
  return v;
}

TEST(MeshIoRead, AllFormatsOfTheBoxGiveTheSameMesh) {
  MeshReadReport ref_report;
  const TetMesh ref = read_mesh(sample("box22.msh"), {}, &ref_report);
  EXPECT_EQ(ref_report.format, "gmsh 2.2");
  EXPECT_EQ(ref_report.skipped_elements, 44);  // the "skin" triangles
  EXPECT_EQ(ref_report.repaired_inverted, 0);
  const std::map<int, std::string> names = {{1, "liver"}, {7, "gallbladder lobe"}};
  EXPECT_EQ(ref_report.group_names, names);  // the 2-D name "skin" is left out
  test::expect_mesh_invariants(ref);

  struct Case {
    const char* file;
    const char* format;
    std::int64_t skipped;
  };
  for (const Case& c : {Case{"box41.msh", "gmsh 4.1", 44}, Case{"box.vtk", "vtk 3.0", 5},
                        Case{"box51.vtk", "vtk 5.1", 3}, Case{"box.node", "tetgen", 0},
                        Case{"box.ele", "tetgen", 0}}) {
    SCOPED_TRACE(c.file);
    MeshReadReport report;
    const TetMesh m = read_mesh(sample(c.file), {}, &report);
    EXPECT_EQ(report.format, c.format);
    EXPECT_EQ(report.skipped_elements, c.skipped);
    test::expect_same_mesh(ref, m);
    test::expect_mesh_invariants(m);
    if (std::string(c.file) == "box41.msh") {
      EXPECT_EQ(report.group_names, names);
    }
  }
}

TEST(MeshIoRead, BoxVolumesPerGroupAreTheGeometry) {
  // Box 1 (group 1) is 20 x 10 x 10 mm, box 2 (group 7) 10 x 10 x 10 mm.
  const auto v = group_volumes(read_mesh(sample("box22.msh")));
  ASSERT_EQ(v.size(), 2U);
  EXPECT_NEAR(v.at(1), 2e-6, 1e-18);
  EXPECT_NEAR(v.at(7), 1e-6, 1e-18);
}

TEST(MeshIoRead, RealTetGenOutput) {
  // tetgen -pq1.414A of a 20 x 10 x 10 mm box: region attribute 1 on every tet.
  const TetMesh m = read_mesh(sample("tetgen_box.node"));
  test::expect_mesh_invariants(m);
  EXPECT_EQ(m.num_nodes(), 319);
  EXPECT_EQ(m.num_tets(), 951);
  const auto v = group_volumes(m);
  ASSERT_EQ(v.size(), 1U);
  EXPECT_NEAR(v.at(1), 2e-6, 1e-18);
}

TEST(MeshIoRead, CrlfLineEndingsReadTheSame) {
  for (const char* file : {"box22.msh", "box41.msh", "box.vtk", "box51.vtk"}) {
    SCOPED_TRACE(file);
    const std::string text = test::slurp(sample(file));
    std::string crlf;
    for (const char c : text) {
      if (c == '\n') crlf.push_back('\r');
      crlf.push_back(c);
    }
    const TetMesh a = read_mesh(sample(file));
    const TetMesh b = read_mesh_text(crlf, MeshFormat::kAuto, file);
    test::expect_same_mesh(a, b);
  }
}

TEST(MeshIoRead, AutoFormatFromNameThenContent) {
  const std::string gmsh = test::slurp(sample("box22.msh"));
  const std::string vtk = test::slurp(sample("box.vtk"));
  EXPECT_EQ(read_mesh_text(gmsh, MeshFormat::kAuto, "no_extension").num_tets(), 961);
  EXPECT_EQ(read_mesh_text(vtk, MeshFormat::kAuto, "no_extension").num_tets(), 961);
  EXPECT_EQ(read_mesh_text(test::slurp(sample("box.node")), MeshFormat::kAuto, "x", {}, nullptr,
                           test::slurp(sample("box.ele")))
                .num_tets(),
            961);
  try {
    (void)read_mesh_text("solid x\nendsolid x\n", MeshFormat::kAuto, "thing");
    ADD_FAILURE();
  } catch (const InputError& e) {
    EXPECT_EQ(e.line(), 0);
    EXPECT_EQ(e.file(), "thing");
  }
}

constexpr const char* kHeader22 = "$MeshFormat\n2.2 0 8\n$EndMeshFormat\n";
constexpr const char* kNodes5 =
    "$Nodes\n5\n1 0 0 0\n2 1 0 0\n3 0 1 0\n4 0 0 1\n5 1 1 1\n$EndNodes\n";

TEST(MeshIoRead, Gmsh22GroupRules) {
  // physical tag, else elementary tag when physical is 0, else 1 without tags.
  const std::string text = std::string(kHeader22) + kNodes5 +
                           "$Elements\n3\n1 4 2 9 4 1 2 3 4\n2 4 2 0 5 2 3 4 5\n"
                           "3 4 0 1 2 3 4\n$EndElements\n";
  const TetMesh m = read_mesh_text(text, MeshFormat::kGmsh, "g.msh");
  ASSERT_EQ(m.num_tets(), 3);
  EXPECT_EQ(m.group[0], 9);
  EXPECT_EQ(m.group[1], 5);
  EXPECT_EQ(m.group[2], 1);
}

TEST(MeshIoRead, Gmsh22SkipsUnknownSectionsAndNonTetElements) {
  const std::string text =
      std::string(kHeader22) + "$Comments\nanything $Nodes here\n$EndComments\n" + kNodes5 +
      "$Elements\n4\n1 15 2 1 1 1\n2 1 2 1 1 1 2\n3 11 2 1 1 1 2 3 4 5 1 2 3 4 5\n"
      "4 4 2 3 3 1 2 3 4\n$EndElements\n$NodeData\n1\n\"t\"\n$EndNodeData\n";
  MeshReadReport report;
  const TetMesh m = read_mesh_text(text, MeshFormat::kGmsh, "g.msh", {}, &report);
  EXPECT_EQ(m.num_tets(), 1);
  EXPECT_EQ(report.skipped_elements, 3);
  EXPECT_EQ(m.num_nodes(), 5);  // unused nodes are kept
}

TEST(MeshIoRead, NodeIdsAreRenumberedInFileOrder) {
  // Sparse, unordered and huge ids (the hash-map path) all map to 0.. in file order.
  for (const std::string ids : {"10 3 7 100 5", "1000000000000 3 -7 99999999999 5"}) {
    SCOPED_TRACE(ids);
    std::istringstream in(ids);
    std::string id[5];
    for (auto& s : id) in >> s;
    const std::string text = std::string(kHeader22) + "$Nodes\n5\n" + id[0] + " 0 0 0\n" + id[1] +
                             " 1 0 0\n" + id[2] + " 0 1 0\n" + id[3] + " 0 0 1\n" + id[4] +
                             " 1 1 1\n$EndNodes\n$Elements\n1\n1 4 2 1 1 " + id[1] + " " + id[2] +
                             " " + id[3] + " " + id[4] + "\n$EndElements\n";
    const TetMesh m = read_mesh_text(text, MeshFormat::kGmsh, "ids.msh");
    EXPECT_EQ(m.tets[0], (Tet{1, 2, 3, 4}));
    EXPECT_EQ(m.rest[3], Vec3(0, 0, 1));
  }
}

constexpr const char* kHeader41 = "$MeshFormat\n4.1 0 8\n$EndMeshFormat\n";

TEST(MeshIoRead, Gmsh41GroupIsVolumePhysicalElseEntityTag) {
  // Volume 1 has physical tag 5, volume 2 none: its tets take the entity tag 2.
  const std::string text =
      std::string(kHeader41) +
      "$Entities\n0 0 0 2\n1 0 0 0 1 1 1 1 5 0\n2 0 0 0 1 1 1 0 0\n$EndEntities\n"
      "$Nodes\n2 5 1 5\n3 1 0 4\n1\n2\n3\n4\n0 0 0\n1 0 0\n0 1 0\n0 0 1\n"
      "2 7 1 1\n5\n0.2 0.3 0 0.4 0.5\n$EndNodes\n"
      "$Elements\n3 3 1 3\n3 1 4 1\n1 1 2 3 4\n3 2 4 1\n2 2 4 3 5\n2 7 2 1\n3 1 2 "
      "3\n$EndElements\n";
  MeshReadReport report;
  const TetMesh m = read_mesh_text(text, MeshFormat::kGmsh, "e.msh", {}, &report);
  ASSERT_EQ(m.num_tets(), 2);
  EXPECT_EQ(m.group[0], 5);
  EXPECT_EQ(m.group[1], 2);
  EXPECT_EQ(report.skipped_elements, 1);
  EXPECT_EQ(m.rest[4], Vec3(0.2, 0.3, 0.0));  // parametric u v on the surface node are skipped
}

TEST(MeshIoRead, Gmsh41WithoutEntitiesUsesEntityTags) {
  const std::string text = std::string(kHeader41) +
                           "$Nodes\n1 4 1 4\n3 9 0 4\n1\n2\n3\n4\n0 0 0\n1 0 0\n0 1 0\n0 0 1\n"
                           "$EndNodes\n$Elements\n1 1 1 1\n3 9 4 1\n1 1 2 3 4\n$EndElements\n";
  EXPECT_EQ(read_mesh_text(text, MeshFormat::kGmsh, "e.msh").group[0], 9);
}

TEST(MeshIoRead, TetGenZeroBasedTenNodeTetsAndComments) {
  const std::string node =
      "# points\n5 3 1 1 # one attribute, one marker\n\n0 0 0 0 7.5 1\n1 1 0 0 0 0\n"
      "2 0 1 0 0 0\n3 0 0 1 0 0\n4 1 1 1 0 1\n";
  // 10-node tets: the first four are the corners; the edge nodes here are just other ids.
  const std::string ele = "2 10 1\n0 0 1 2 3 4 4 4 4 4 4 3\n1 1 2 3 4 0 0 0 0 0 0 12\n";
  const TetMesh m = read_mesh_text(node, MeshFormat::kTetGen, "t.node", {}, nullptr, ele);
  ASSERT_EQ(m.num_tets(), 2);
  EXPECT_EQ(m.tets[0], (Tet{0, 1, 2, 3}));
  EXPECT_EQ(m.tets[1], (Tet{1, 2, 3, 4}));
  EXPECT_EQ(m.group[0], 3);
  EXPECT_EQ(m.group[1], 12);
}

// A negative region is not a group: the error names the .ele file and its line.
TEST(MeshIoRead, TetGenNegativeRegionIsAnError) {
  const std::string node = "4 3 0 0\n1 0 0 0\n2 1 0 0\n3 0 1 0\n4 0 0 1\n";
  const std::string ele = "1 4 1\n1 1 2 3 4 -3\n";
  try {
    (void)read_mesh_text(node, MeshFormat::kTetGen, "t.node", {}, nullptr, ele);
    ADD_FAILURE();
  } catch (const InputError& e) {
    EXPECT_EQ(e.file(), "t.ele");
    EXPECT_EQ(e.line(), 2);
  }
}

TEST(MeshIoRead, VtkGroupPrefersGroupOverGmshPhysical) {
  const std::string text =
      "# vtk DataFile Version 4.2\nt\nascii\nDATASET UNSTRUCTURED_GRID\nPOINTS 5 float\n"
      "0 0 0 1 0 0 0 1 0 0 0 1 1 1 1\nCELLS 3 12\n4 0 1 2 3\n4 1 2 3 4\n1 4\n"
      "CELL_TYPES 3\n10 10 1\nCELL_DATA 3\nFIELD f 2\ngmsh:physical 1 3 int\n8 8 8\n"
      "group 1 3 double\n2 3 4\nPOINT_DATA 5\nNORMALS n float\n0 0 1 0 0 1 0 0 1 0 0 1 0 0 1\n";
  MeshReadReport report;
  const TetMesh m = read_mesh_text(text, MeshFormat::kVtk, "v.vtk", {}, &report);
  ASSERT_EQ(m.num_tets(), 2);
  EXPECT_EQ(m.group[0], 2);
  EXPECT_EQ(m.group[1], 3);
  EXPECT_EQ(report.skipped_elements, 1);
  EXPECT_EQ(report.format, "vtk 4.2");
}

TEST(MeshIoRead, VtkWithoutGroupArrayIsGroupOne) {
  const std::string text =
      "# vtk DataFile Version 2.0\nt\nASCII\nDATASET UNSTRUCTURED_GRID\nPOINTS 4 double\n"
      "0 0 0\n1 0 0\n0 1 0\n0 0 1\nCELLS 1 5\n4 0 1 2 3\nCELL_TYPES 1\n10\n";
  EXPECT_EQ(read_mesh_text(text, MeshFormat::kVtk, "v.vtk").group[0], 1);
}

}  // namespace
}  // namespace serosa
