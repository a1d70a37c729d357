// check_mesh (engine/mesh_check.h): volumes and counts on boxes, every kind of broken mesh
// reported (never a crash), and consistency of the counts on random garbage.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <random>
#include <string>

#include "engine/box_meshes.h"
#include "engine/mesh_check.h"

namespace serosa {
namespace {

bool mentions(const std::vector<std::string>& lines, const std::string& word) {
  return std::any_of(lines.begin(), lines.end(),
                     [&](const std::string& s) { return s.find(word) != std::string::npos; });
}

TEST(CheckMesh, SubdividedCubesSumToTheCube) {
  const Vec3 lo(0.1, -0.2, 0.3), hi(0.15, -0.1, 0.32);
  const double box = (hi - lo).prod();
  for (const auto& split : {fixtures::five_tets(), fixtures::kuhn_tets()}) {
    const TetMesh m = fixtures::cube_mesh(split, lo, hi);
    const MeshCheckReport r = check_mesh(m);
    EXPECT_TRUE(r.valid);
    EXPECT_TRUE(r.problems.empty());
    EXPECT_EQ(r.nodes, 8);
    EXPECT_EQ(r.tets, static_cast<std::int64_t>(split.size()));
    EXPECT_NEAR(r.volume_m3, box, 1e-12 * box);
    ASSERT_EQ(r.group_volume_m3.size(), 1U);
    EXPECT_NEAR(r.group_volume_m3.at(1), box, 1e-12 * box);
    EXPECT_EQ(r.boundary_faces, 12);
    EXPECT_EQ(r.overshared_faces, 0);
    EXPECT_EQ(r.misoriented_faces, 0);
    EXPECT_EQ(r.inverted_tets, 0);
    EXPECT_EQ(r.flat_tets, 0);
    EXPECT_EQ(r.unreferenced_nodes, 0);
    EXPECT_GT(r.min_quality, 0.0);
    EXPECT_LE(r.min_quality, r.median_quality);
    EXPECT_LE(r.median_quality, 1.0);
    EXPECT_TRUE(r.bbox_min.isApprox(lo));
    EXPECT_TRUE(r.bbox_max.isApprox(hi));
  }
  // The 5-split's central tet is regular for a unit cube; its corners are not.
  const MeshCheckReport r5 = check_mesh(fixtures::cube_mesh(fixtures::five_tets()));
  EXPECT_LT(r5.min_quality, 1.0);
}

TEST(CheckMesh, RandomGridsAreValidAndVolumesAddUpPerGroup) {
  std::mt19937 rng(5);
  for (int trial = 0; trial < 30; ++trial) {
    const int k = 1 + trial % 4;
    const auto xs = test_meshes::random_spacing(rng, k, 0.2);
    const auto ys = test_meshes::random_spacing(rng, k, 0.1);
    const auto zs = test_meshes::random_spacing(rng, k, 0.05);
    const TetMesh m = test_meshes::kuhn_lattice(xs, ys, zs, 2);
    const MeshCheckReport r = check_mesh(m);
    EXPECT_TRUE(r.valid) << (r.problems.empty() ? "" : r.problems[0]);
    EXPECT_NEAR(r.volume_m3, 0.2 * 0.1 * 0.05, 1e-15);
    EXPECT_EQ(r.tets, 6 * k * k * k);
    EXPECT_EQ(r.boundary_faces, 12 * k * k);
    EXPECT_EQ(r.overshared_faces, 0);
    EXPECT_EQ(r.misoriented_faces, 0);
    EXPECT_EQ(4 * r.tets, r.boundary_faces + 2 * r.interior_faces);
    // Group g holds the cube columns i with i % 2 == g - 1.
    double expected_g1 = 0.0;
    for (int i = 0; i < k; i += 2)
      expected_g1 += xs[static_cast<std::size_t>(i + 1)] - xs[static_cast<std::size_t>(i)];
    expected_g1 *= 0.1 * 0.05;
    EXPECT_NEAR(r.group_volume_m3.at(1), expected_g1, 1e-15);
    double total = 0.0;
    std::int64_t tets = 0;
    for (const auto& [g, v] : r.group_volume_m3) total += v;
    for (const auto& [g, n] : r.group_tets) tets += n;
    EXPECT_NEAR(total, r.volume_m3, 1e-15);
    EXPECT_EQ(tets, r.tets);
  }
}

TEST(CheckMesh, DuplicatedTetReportsOversharedFaces) {
  for (const auto& split : {fixtures::five_tets(), fixtures::kuhn_tets()}) {
    for (std::size_t which = 0; which < split.size(); ++which) {
      TetMesh m = fixtures::cube_mesh(split);
      m.add_tet(m.tets[which], 1);
      const MeshCheckReport r = check_mesh(m);
      EXPECT_FALSE(r.valid);
      EXPECT_GT(r.overshared_faces, 0);
      EXPECT_EQ(r.duplicate_tets, 1);
      EXPECT_TRUE(mentions(r.problems, "more than two tets"));
      EXPECT_TRUE(mentions(r.problems, "duplicated"));
    }
  }
}

TEST(CheckMesh, DuplicatedLoneTetIsCaughtWithoutOversharing) {
  TetMesh m = fixtures::cube_mesh({{0, 1, 2, 4}});
  m.add_tet(m.tets[0], 1);
  const MeshCheckReport r = check_mesh(m);
  EXPECT_FALSE(r.valid);
  EXPECT_EQ(r.overshared_faces, 0);
  EXPECT_EQ(r.duplicate_tets, 1);
  EXPECT_EQ(r.misoriented_faces, 4);
}

TEST(CheckMesh, InvertedAndFlatTetsAreCounted) {
  TetMesh m = fixtures::cube_mesh(fixtures::kuhn_tets());
  std::swap(m.tets[2][0], m.tets[2][1]);
  MeshCheckReport r = check_mesh(m);
  EXPECT_FALSE(r.valid);
  EXPECT_EQ(r.inverted_tets, 1);
  EXPECT_LT(r.min_quality, 0.0);
  EXPECT_TRUE(mentions(r.problems, "inverted tets (first tet: 2"));
  EXPECT_GT(r.misoriented_faces, 0);

  TetMesh f = fixtures::cube_mesh(fixtures::kuhn_tets());
  f.add_tet({0, 1, 3, 2}, 1);  // four corners of the bottom face: zero volume
  r = check_mesh(f);
  EXPECT_FALSE(r.valid);
  EXPECT_EQ(r.flat_tets, 1);
  EXPECT_EQ(r.inverted_tets, 0);
  EXPECT_EQ(r.min_quality, 0.0);
  EXPECT_TRUE(mentions(r.problems, "flat"));

  TetMesh rep = fixtures::cube_mesh(fixtures::kuhn_tets());
  rep.add_tet({0, 0, 1, 2}, 1);  // repeated node
  r = check_mesh(rep);
  EXPECT_EQ(r.flat_tets, 1);
  EXPECT_FALSE(r.valid);
}

TEST(CheckMesh, BrokenStructureIsReportedNotCrashed) {
  TetMesh bad_id = fixtures::cube_mesh(fixtures::kuhn_tets());
  bad_id.add_tet({0, 1, 2, 99}, 1);
  bad_id.add_tet({-1, 1, 2, 3}, 1);
  MeshCheckReport r = check_mesh(bad_id);
  EXPECT_FALSE(r.valid);
  EXPECT_EQ(r.bad_tets, 2);
  EXPECT_TRUE(mentions(r.problems, "out of range (first tet: 6, ids 0 1 2 99 with 8 nodes"));
  EXPECT_NEAR(r.volume_m3, 1.0, 1e-12);  // bad tets left out

  TetMesh nan = fixtures::cube_mesh(fixtures::kuhn_tets());
  nan.rest[3].y() = std::numeric_limits<double>::quiet_NaN();
  r = check_mesh(nan);
  EXPECT_FALSE(r.valid);
  EXPECT_EQ(r.nonfinite_nodes, 1);
  EXPECT_TRUE(std::isfinite(r.volume_m3));
  EXPECT_TRUE(std::isfinite(r.min_quality));

  TetMesh sizes = fixtures::cube_mesh(fixtures::kuhn_tets());
  sizes.group.pop_back();
  r = check_mesh(sizes);
  EXPECT_FALSE(r.valid);
  EXPECT_TRUE(mentions(r.problems, "group has 5 entries, expected 6"));

  r = check_mesh(TetMesh{});
  EXPECT_FALSE(r.valid);
  EXPECT_TRUE(mentions(r.problems, "no tetrahedra"));
  EXPECT_EQ(r.min_quality, 0.0);
}

TEST(CheckMesh, UnreferencedNodesWarnButStayValid) {
  TetMesh m = fixtures::cube_mesh(fixtures::kuhn_tets());
  m.add_node(Vec3(5, 5, 5));
  const MeshCheckReport r = check_mesh(m);
  EXPECT_TRUE(r.valid);
  EXPECT_EQ(r.unreferenced_nodes, 1);
  EXPECT_TRUE(mentions(r.warnings, "node: 8"));
}

TEST(CheckMesh, RandomGarbageGivesConsistentCounts) {
  std::mt19937 rng(9);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  for (int trial = 0; trial < 2000; ++trial) {
    TetMesh m;
    const int n = static_cast<int>(rng() % 12);
    for (int i = 0; i < n; ++i) {
      Vec3 p(u(rng), u(rng), u(rng));
      if (rng() % 50 == 0) p.z() = std::numeric_limits<double>::infinity();
      m.add_node(p);
    }
    std::uniform_int_distribution<int> id(-1, n);
    const int tets = static_cast<int>(rng() % 20);
    for (int i = 0; i < tets; ++i)
      m.add_tet({id(rng), id(rng), id(rng), id(rng)}, static_cast<std::uint16_t>(rng() % 3));
    const MeshCheckReport r = check_mesh(m);
    EXPECT_EQ(r.valid, r.problems.empty());
    EXPECT_EQ(r.nodes, n);
    EXPECT_EQ(r.tets, tets);
    EXPECT_LE(r.boundary_faces + 2 * r.interior_faces + 3 * r.overshared_faces, 4 * r.tets);
    EXPECT_LE(r.inverted_tets + r.flat_tets + r.bad_tets, r.tets);
    EXPECT_GE(r.min_quality, -1.0);
    EXPECT_LE(r.median_quality, 1.0);
    EXPECT_TRUE(std::isfinite(r.volume_m3));
    if (r.inverted_tets + r.flat_tets + r.bad_tets + r.nonfinite_nodes + r.duplicate_tets > 0) {
      EXPECT_FALSE(r.valid);
    }
  }
}

}  // namespace
}  // namespace serosa
