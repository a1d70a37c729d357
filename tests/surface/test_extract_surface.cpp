// extract_surface (paper Figure 10, Thrust OpenMP backend; CUDA when a device is present) against
// a brute-force std::map reference on random and structured meshes.
#include <gtest/gtest.h>
#include <omp.h>

#include <climits>
#include <random>
#include <stdexcept>

#include "engine/tet_faces.h"
#include "surface/extract_surface.h"
#include "surface/face_key.h"
#include "surface/validate_surface.h"
#include "surface_fixtures.h"

namespace serosa::surface {
namespace {

using test_meshes::kuhn_box;
using testing::random_mesh;
using testing::records;
using testing::reference_boundary;

void expect_valid(const SurfaceMesh& s, const TetMesh& m) {
  const auto errs = validate_surface(s, m);
  EXPECT_TRUE(errs.empty()) << errs.front();
}

/// Every face's normal, in rest space, points away from its tet's fourth node.
void expect_outward(const SurfaceMesh& s, const TetMesh& m) {
  for (std::int32_t i = 0; i < s.num_faces(); ++i) {
    const Tri& f = s.faces[i];
    const Tet& t = m.tets[s.face_tet[i]];
    std::int32_t opposite = -1;
    for (std::int32_t v : t)
      if (v != f[0] && v != f[1] && v != f[2]) opposite = v;
    ASSERT_GE(opposite, 0);
    const Vec3 n = (m.rest[f[1]] - m.rest[f[0]]).cross(m.rest[f[2]] - m.rest[f[0]]);
    EXPECT_LT(n.dot(m.rest[opposite] - m.rest[f[0]]), 0.0) << "face " << i;
  }
}

TEST(ExtractSurface, EmptyMesh) {
  const TetMesh m;
  const SurfaceMesh s = extract_surface(m);
  EXPECT_EQ(s.num_faces(), 0);
  EXPECT_TRUE(s.groups.empty());
  expect_valid(s, m);
}

TEST(ExtractSurface, OneTetGivesFourOutwardFaces) {
  TetMesh m;
  m.add_node(Vec3(0, 0, 0));
  m.add_node(Vec3(1, 0, 0));
  m.add_node(Vec3(0, 1, 0));
  m.add_node(Vec3(0, 0, 1));
  m.add_tet({0, 1, 2, 3}, 7);
  m.topology_version = 5;
  const SurfaceMesh s = extract_surface(m);
  ASSERT_EQ(s.num_faces(), 4);
  ASSERT_EQ(s.groups.size(), 1u);
  EXPECT_EQ(s.groups[0].group, 7);
  EXPECT_EQ(s.groups[0].offset, 0);
  EXPECT_EQ(s.groups[0].count, 4);
  EXPECT_EQ(s.topology_version, 5u);
  for (std::int32_t t : s.face_tet) EXPECT_EQ(t, 0);
  expect_valid(s, m);
  expect_outward(s, m);
  EXPECT_EQ(records(s), reference_boundary(m));
}

// outward_face is the device form of engine's face table (nvcc compiles no Eigen, so it cannot
// include engine/tet_faces.h): the same faces, in the same winding.
TEST(ExtractSurface, OutwardFaceIsEnginesFaceTable) {
  const Tet t{10, 11, 12, 13};
  for (int l = 0; l < 4; ++l) {
    Tri f{};
    outward_face(t, l, f[0], f[1], f[2]);
    EXPECT_EQ(f, tet_face(t, l)) << l;
  }
}

TEST(ExtractSurface, TwoTetsShareOneFace) {
  TetMesh m;
  m.add_node(Vec3(0, 0, 0));
  m.add_node(Vec3(1, 0, 0));
  m.add_node(Vec3(0, 1, 0));
  m.add_node(Vec3(0, 0, 1));
  m.add_node(Vec3(0, 0, -1));
  m.add_tet({0, 1, 2, 3}, 1);
  m.add_tet({0, 2, 1, 4}, 2);
  const SurfaceMesh s = extract_surface(m);
  EXPECT_EQ(s.num_faces(), 6);
  ASSERT_EQ(s.groups.size(), 2u);
  EXPECT_EQ(s.groups[0].count, 3);
  EXPECT_EQ(s.groups[1].count, 3);
  expect_valid(s, m);
  expect_outward(s, m);
  EXPECT_EQ(records(s), reference_boundary(m));
}

TEST(ExtractSurface, GridMatchesReference) {
  // The last grid (27,648 tets) is above the serial cutoff: the OpenMP path.
  for (const auto& [nx, ny, nz, groups] : std::vector<std::array<int, 4>>{
           {1, 1, 1, 1}, {3, 2, 1, 1}, {4, 4, 4, 2}, {7, 5, 3, 4}, {24, 16, 12, 5}}) {
    const TetMesh m = kuhn_box(nx, ny, nz, groups);
    const SurfaceMesh s = extract_surface(m);
    // A box's surface: 2 triangles per unit square of its six sides.
    EXPECT_EQ(s.num_faces(), 4 * (nx * ny + ny * nz + nz * nx));
    EXPECT_EQ(static_cast<int>(s.groups.size()), groups);
    expect_valid(s, m);
    expect_outward(s, m);
    EXPECT_EQ(records(s), reference_boundary(m));
  }
}

TEST(ExtractSurface, ThousandsOfRandomMeshesMatchReference) {
  std::mt19937 rng(2015);
  for (int trial = 0; trial < 3000; ++trial) {
    const int nodes = 5 + trial % 20;
    const int tets = 1 + static_cast<int>(rng() % 40);
    const TetMesh m = random_mesh(rng, nodes, tets, 1 + trial % 4);
    // Small meshes run serially by default; force OpenMP on every tenth.
    const SurfaceMesh s =
        extract_surface_cpu(m, {.serial_below_tets = trial % 10 == 0 ? 0 : 16384});
    ASSERT_EQ(records(s), reference_boundary(m)) << "trial " << trial;
    expect_valid(s, m);
    expect_outward(s, m);
    if (::testing::Test::HasFailure()) FAIL() << "trial " << trial;
  }
}

TEST(ExtractSurface, InsideAGroupFacesAreInKeyOrderAndDeterministic) {
  const TetMesh m = kuhn_box(5, 4, 3, 3);
  const SurfaceMesh a = extract_surface(m);
  for (const GroupRange& r : a.groups)
    for (std::int32_t i = r.offset + 1; i < r.offset + r.count; ++i)
      EXPECT_LT(make_face_key<NarrowKey>(a.faces[i - 1][0], a.faces[i - 1][1], a.faces[i - 1][2]),
                make_face_key<NarrowKey>(a.faces[i][0], a.faces[i][1], a.faces[i][2]));
  // Same result serially and with one and two OpenMP threads.
  const int threads = omp_get_max_threads();
  omp_set_num_threads(1);
  const SurfaceMesh one = extract_surface_cpu(m, {.serial_below_tets = 0});
  omp_set_num_threads(2);
  const SurfaceMesh two = extract_surface_cpu(m, {.serial_below_tets = 0});
  omp_set_num_threads(threads);
  EXPECT_EQ(one.faces, a.faces);
  EXPECT_EQ(two.faces, a.faces);
  EXPECT_EQ(two.face_tet, a.face_tet);
}

TEST(ExtractSurface, WideKeysGiveTheSameSurface) {
  std::mt19937 rng(7);
  for (int trial = 0; trial < 200; ++trial) {
    const TetMesh m = random_mesh(rng, 12, 30, 3);
    const SurfaceMesh narrow = extract_surface_cpu(m);
    const SurfaceMesh wide = extract_surface_cpu(m, {.keys = KeyWidth::kWide});
    ASSERT_EQ(narrow.faces, wide.faces);
    ASSERT_EQ(narrow.face_tet, wide.face_tet);
    ASSERT_EQ(narrow.face_group, wide.face_group);
  }
  const TetMesh g = kuhn_box(6, 5, 4, 3);
  EXPECT_EQ(extract_surface_cpu(g, {.keys = KeyWidth::kWide, .serial_below_tets = 0}).faces,
            extract_surface_cpu(g).faces);
}

TEST(ExtractSurface, NodeIdsBeyondTwentyOneBitsAreExact) {
  // Ids that would collide if packed into 21 bits each; only the topology is read, so the tets
  // may name nodes the (empty) node arrays do not hold.
  constexpr std::int32_t kBig = INT32_MAX;
  constexpr std::int32_t k21 = 1 << 21;
  TetMesh m;
  m.add_tet({kBig - 3, kBig - 2, kBig - 1, kBig}, 1);
  m.add_tet({kBig - 3, kBig - 1, kBig - 2, 0}, 1);  // shares face {kBig-3, kBig-2, kBig-1}
  // Packed into 21 bits each, face {1, 2, 2^21 + 10} would read as {1, 3, 10}: these two tets
  // share no face, so all 8 of their faces are boundary faces.
  m.add_tet({1, 2, k21 + 10, 50}, 2);
  m.add_tet({1, 3, 10, 60}, 2);
  const SurfaceMesh s = extract_surface(m);
  EXPECT_EQ(s.num_faces(), 6 + 4 + 4);
  EXPECT_EQ(records(s), reference_boundary(m));
}

TEST(ExtractSurface, RejectsNegativeNodeIds) {
  TetMesh m;
  m.add_tet({0, 1, 2, -1}, 1);
  EXPECT_THROW((void)extract_surface(m), std::invalid_argument);
}

TEST(ExtractSurfaceCuda, MatchesOpenMpWhenADeviceIsPresent) {
  if (!cuda_available()) {
    EXPECT_THROW((void)extract_surface(kuhn_box(1, 1, 1), Backend::kCuda), std::runtime_error);
#if defined(SEROSA_HAVE_CUDA)
    GTEST_SKIP() << "CUDA backend built, but no CUDA device is present: GPU comparison skipped";
#else
    GTEST_SKIP() << "built without CUDA (nvcc not found): GPU comparison skipped";
#endif
  }
  std::mt19937 rng(11);
  for (int trial = 0; trial < 200; ++trial) {
    const TetMesh m = random_mesh(rng, 5 + trial % 20, 1 + trial % 40, 1 + trial % 3);
    const SurfaceMesh cpu = extract_surface(m, Backend::kCpu);
    const SurfaceMesh gpu = extract_surface(m, Backend::kCuda);
    ASSERT_EQ(cpu.faces, gpu.faces) << "trial " << trial;
    ASSERT_EQ(cpu.face_tet, gpu.face_tet);
    ASSERT_EQ(cpu.face_group, gpu.face_group);
  }
  for (KeyWidth keys : {KeyWidth::kAuto, KeyWidth::kWide}) {
    const TetMesh g = kuhn_box(30, 20, 10, 3);
    const SurfaceMesh cpu = extract_surface_cpu(g, {.keys = keys});
    const SurfaceMesh gpu = extract_surface_cuda(g, keys);
    EXPECT_EQ(cpu.faces, gpu.faces);
    EXPECT_EQ(cpu.face_tet, gpu.face_tet);
    ASSERT_EQ(cpu.groups.size(), gpu.groups.size());
    for (std::size_t i = 0; i < cpu.groups.size(); ++i) {
      EXPECT_EQ(cpu.groups[i].group, gpu.groups[i].group);
      EXPECT_EQ(cpu.groups[i].offset, gpu.groups[i].offset);
      EXPECT_EQ(cpu.groups[i].count, gpu.groups[i].count);
    }
  }
}

}  // namespace
}  // namespace serosa::surface
