// Round trips through write_gmsh22: every sample format, and thousands of random meshes, read back
// bit for bit (positions), with the same tets, groups and group names.
#include <gtest/gtest.h>

#include <filesystem>
#include <limits>
#include <map>
#include <random>
#include <stdexcept>
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

TEST(MeshIoRoundTrip, EverySampleFormatThroughGmsh22) {
  test::ScratchDir dir;
  for (const char* file :
       {"box22.msh", "box41.msh", "box.vtk", "box51.vtk", "box.node", "tetgen_box.node"}) {
    SCOPED_TRACE(file);
    MeshReadReport in_report;
    const TetMesh a = read_mesh(sample(file), {}, &in_report);
    write_gmsh22(dir / "out.msh", a, false, in_report.group_names);
    MeshReadReport back_report;
    const TetMesh b = read_mesh(dir / "out.msh", {}, &back_report);
    test::expect_same_mesh(a, b);
    EXPECT_EQ(back_report.group_names, in_report.group_names);
    EXPECT_EQ(back_report.skipped_elements, 0);
  }
}

TEST(MeshIoRoundTrip, ThousandsOfRandomMeshesAreExact) {
  test::ScratchDir dir;
  std::mt19937 rng(20251123);
  std::uniform_int_distribution<int> nodes(4, 60);
  for (int trial = 0; trial < 2000; ++trial) {
    const int n = nodes(rng);
    const TetMesh a = test::random_valid_mesh(rng, n, 1 + trial % 50);
    // Fresh names: ext4 flushes a file truncated and rewritten when it is closed.
    const fs::path path = dir / test::numbered("r", trial, ".msh");
    write_gmsh22(path, a);
    const TetMesh b = read_mesh(path);
    test::expect_same_mesh(a, b);
    if (::testing::Test::HasFatalFailure()) {
      FAIL() << "trial " << trial;
    }
  }
}

TEST(MeshIoRoundTrip, ExtremeButFiniteNumbersAreExact) {
  // Doubles with full 17-digit mantissas, tiny and huge magnitudes, negative zero.
  test::ScratchDir dir;
  TetMesh a;
  const double e = std::numeric_limits<double>::epsilon();
  a.add_node(Vec3(-0.0, 1.0 / 3.0, 1e-300));
  a.add_node(Vec3(1.0 + e, 2.0 / 3.0, 1e-300));
  a.add_node(Vec3(0.1, 0.7 + 1e-16, 1e-300));
  a.add_node(Vec3(0.3, 0.2, 1.0 + 4 * e));
  a.add_node(Vec3(1e30, -1e30, 1e30 / 3.0));
  if (a.rest_volume(a.add_tet({0, 1, 2, 3}, 65535)) < 0) std::swap(a.tets[0][2], a.tets[0][3]);
  write_gmsh22(dir / "x.msh", a);
  const TetMesh b = read_mesh(dir / "x.msh");
  test::expect_same_mesh(a, b);
  EXPECT_TRUE(std::signbit(b.rest[0].x()));
}

TEST(MeshIoRoundTrip, CurrentPositionsOnRequest) {
  test::ScratchDir dir;
  std::mt19937 rng(7);
  TetMesh a = test::random_valid_mesh(rng, 10, 5);
  // A rigid shift keeps every tet's orientation.
  for (auto& x : a.x) x += Vec3(0.5, -2.0, 3.25);
  write_gmsh22(dir / "cur.msh", a, /*current=*/true);
  const TetMesh b = read_mesh(dir / "cur.msh");
  for (std::size_t i = 0; i < a.x.size(); ++i) EXPECT_EQ(b.rest[i], a.x[i]);
}

TEST(MeshIoRoundTrip, GroupNamesWithSpacesAndQuotes) {
  test::ScratchDir dir;
  std::mt19937 rng(3);
  const TetMesh a = test::random_valid_mesh(rng, 8, 3);
  const std::map<int, std::string> names = {
      {1, "right lobe"}, {2, "the \"cystic\" duct"}, {40000, "x"}};
  write_gmsh22(dir / "n.msh", a, false, names);
  MeshReadReport report;
  (void)read_mesh(dir / "n.msh", {}, &report);
  const std::map<int, std::string> expected = {
      {1, "right lobe"}, {2, "the 'cystic' duct"}, {40000, "x"}};
  EXPECT_EQ(report.group_names, expected);
}

TEST(MeshIoRoundTrip, WriterRefusesWhatCouldNotBeReadBack) {
  test::ScratchDir dir;
  std::mt19937 rng(5);
  TetMesh a = test::random_valid_mesh(rng, 8, 3);
  TetMesh nan = a;
  nan.x[2].y() = std::numeric_limits<double>::quiet_NaN();
  EXPECT_THROW(write_gmsh22(dir / "a.msh", nan, true), std::invalid_argument);
  TetMesh bad_id = a;
  bad_id.tets[1][2] = 8;
  EXPECT_THROW(write_gmsh22(dir / "b.msh", bad_id), std::invalid_argument);
  TetMesh bad_groups = a;
  bad_groups.group.pop_back();
  EXPECT_THROW(write_gmsh22(dir / "c.msh", bad_groups), std::invalid_argument);
  EXPECT_THROW(write_gmsh22(dir / "no_such_dir" / "d.msh", a), std::runtime_error);
}

}  // namespace
}  // namespace serosa
