// TetBvh: the same candidates as brute force (after build and after refit), and cut_mesh through
// the BVH gives the same delta as through brute force.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdio>
#include <random>
#include <stdexcept>

#include "cut_helpers.h"
#include "cutting/tet_bvh.h"
#include "mesh_fixtures.h"

namespace serosa::cutting {
namespace {

std::vector<std::int32_t> sorted_query(const TetBoxQuery& q, const Vec3& lo, const Vec3& hi) {
  std::vector<std::int32_t> out;
  q(lo, hi, out);
  std::sort(out.begin(), out.end());
  return out;
}

TEST(TetBvh, MatchesBruteForceBeforeAndAfterRefit) {
  TetMesh m = test_meshes::kuhn_cube(5, 1.0, 0.2, 3);
  TetBvh bvh(m);
  std::mt19937 rng(2);
  std::uniform_real_distribution<double> u(-0.5, 5.5), s(0.0, 1.5);
  for (int round = 0; round < 2; ++round) {
    for (int i = 0; i < 500; ++i) {
      const Vec3 lo(u(rng), u(rng), u(rng));
      const Vec3 hi = lo + Vec3(s(rng), s(rng), s(rng));
      EXPECT_EQ(sorted_query(bvh.as_query(), lo, hi), sorted_query(brute_force_query(m), lo, hi));
    }
    // Move the nodes (a shear) and refit.
    for (Vec3& x : m.x) x += Vec3(0.3 * x.z(), 0.0, 0.1 * x.x());
    bvh.refit(m);
  }
  TetMesh cut = m;
  cut.add_tet(m.tets[0], 1);
  EXPECT_THROW(bvh.refit(cut), std::invalid_argument);
}

TEST(TetBvh, CutThroughBvhEqualsBruteForce) {
  const TetMesh m = test_meshes::kuhn_cube(4, 1.0, 0.1, 8);
  const TetBvh bvh(m);
  std::mt19937 rng(4);
  std::normal_distribution<double> g;
  std::uniform_real_distribution<double> u(0.5, 3.5);
  for (int i = 0; i < 50; ++i) {
    const ConvexPolygon blade =
        testing::square(Vec3(g(rng), g(rng), g(rng)), Vec3(u(rng), u(rng), u(rng)), 0.4 + 0.1 * i);
    const CutResult a = cut_mesh(m, blade, {}, bvh.as_query());
    const CutResult b = cut_mesh(m, blade);
    EXPECT_EQ(a.delta.removed_tets, b.delta.removed_tets);
    EXPECT_EQ(a.delta.added_tets, b.delta.added_tets);
    EXPECT_EQ(a.stats.candidates, b.stats.candidates);
  }
}

}  // namespace
}  // namespace serosa::cutting

namespace serosa::cutting {
namespace {

// After each of many cuts (full, partial, repeated in one place so leaves overflow and split),
// the locally updated BVH answers exactly as brute force, and stays shallow.
TEST(TetBvh, LocalUpdateAfterCutsMatchesBruteForce) {
  TetMesh m = test_meshes::kuhn_cube(4, 1.0, 0.1, 5);
  TetBvh bvh(m);
  std::mt19937 rng(6);
  std::normal_distribution<double> g;
  std::uniform_real_distribution<double> u(0.3, 3.7), s(0.0, 1.0);
#if defined(__SANITIZE_ADDRESS__)
  const int cuts = 10;
#else
  const int cuts = 15;
#endif
  for (int i = 0; i < cuts; ++i) {
    const Vec3 c = i % 3 == 0 ? Vec3(2.0, 2.0, 2.0) + 0.01 * Vec3(g(rng), g(rng), g(rng))
                              : Vec3(u(rng), u(rng), u(rng));
    const ConvexPolygon blade =
        testing::square(Vec3(g(rng), g(rng), g(rng)), c, i % 2 == 0 ? 50.0 : 0.7, 0.3 * i);
    CutResult r = cut_mesh(m, blade, {}, bvh.as_query());
    apply(m, r.delta);
    bvh.update(m, r.delta);
    ASSERT_EQ(bvh.num_tets(), m.num_tets());
    for (int q = 0; q < 40; ++q) {
      const Vec3 lo(u(rng) - 0.5, u(rng) - 0.5, u(rng) - 0.5);
      const Vec3 hi = lo + Vec3(s(rng), s(rng), s(rng));
      ASSERT_EQ(sorted_query(bvh.as_query(), lo, hi), sorted_query(brute_force_query(m), lo, hi))
          << "cut " << i;
    }
  }
  std::printf("BVH depth after %d cuts: %d (bound %d)\n", cuts, bvh.depth(), bvh.max_depth());
  EXPECT_LE(bvh.depth(), bvh.max_depth());
  // Refit after node motion still works on the updated tree.
  for (Vec3& x : m.x) x += Vec3(0.2 * x.y(), 0.0, 0.0);
  bvh.refit(m);
  const Vec3 lo(1, 1, 1), hi(2, 2.5, 2);
  EXPECT_EQ(sorted_query(bvh.as_query(), lo, hi), sorted_query(brute_force_query(m), lo, hi));
  // A delta that was not applied is refused.
  CutResult r = cut_mesh(m, testing::square(Vec3::UnitX(), Vec3(1.5, 2, 2), 50.0));
  EXPECT_THROW(bvh.update(m, r.delta), std::invalid_argument);
}

}  // namespace
}  // namespace serosa::cutting

namespace serosa::cutting {
namespace {

// 200 small cuts, a quarter of them in one corner (so the local inserts pile into a few leaves):
// after every cut the updated BVH answers exactly as brute force, and its depth stays within
// max_depth() = 2 ceil(log2(m / 4 + 1)) + 2 because deep paths are rebuilt.
TEST(TetBvh, TwoHundredCutsStayExactAndShallow) {
  TetMesh m = test_meshes::kuhn_cube(5, 1.0, 0.1, 7);
  TetBvh bvh(m);
  std::mt19937 rng(10);
  std::normal_distribution<double> g;
  std::uniform_real_distribution<double> u(0.4, 1.6), v(0.3, 4.7), s(0.0, 1.0), w(-0.5, 5.5);
  std::int32_t deepest = 0;
  for (int i = 0; i < 200; ++i) {
    const Vec3 c = i % 4 == 0 ? Vec3(u(rng), u(rng), u(rng)) : Vec3(v(rng), v(rng), v(rng));
    const ConvexPolygon blade = testing::square(Vec3(g(rng), g(rng), g(rng)), c, 0.15, 0.7 * i);
    CutResult r = cut_mesh(m, blade, {}, bvh.as_query());
    apply(m, r.delta);
    bvh.update(m, r.delta);
    ASSERT_EQ(bvh.num_tets(), m.num_tets());
    deepest = std::max(deepest, bvh.depth());
    ASSERT_LE(bvh.depth(), bvh.max_depth()) << "cut " << i << ", " << m.num_tets() << " tets";
    const int queries = i % 20 == 19 ? 40 : 3;
    for (int q = 0; q < queries; ++q) {
      const Vec3 lo = q % 2 == 0 ? Vec3(w(rng), w(rng), w(rng)) : c - Vec3::Constant(0.3);
      const Vec3 hi = lo + Vec3(s(rng), s(rng), s(rng));
      ASSERT_EQ(sorted_query(bvh.as_query(), lo, hi), sorted_query(brute_force_query(m), lo, hi))
          << "cut " << i;
    }
  }
  std::printf("BVH after 200 cuts: %d tets, depth %d (deepest seen %d, bound %d), %lld rebuilds\n",
              m.num_tets(), bvh.depth(), deepest, bvh.max_depth(),
              static_cast<long long>(bvh.rebuilds()));
  RecordProperty("bvh_depth_after_200_cuts", bvh.depth());
  RecordProperty("bvh_rebuilds", static_cast<int>(bvh.rebuilds()));
  EXPECT_GT(m.num_tets(), 750 * 3);  // the cuts did grow the mesh a lot
  EXPECT_GT(bvh.rebuilds(), 0);      // and the bound was needed
  // Refit keeps working on the rebuilt tree.
  for (Vec3& x : m.x) x += Vec3(0.1 * x.y(), 0.0, 0.05 * x.x());
  bvh.refit(m);
  for (int q = 0; q < 40; ++q) {
    const Vec3 lo(w(rng), w(rng), w(rng));
    const Vec3 hi = lo + Vec3(s(rng), s(rng), s(rng));
    ASSERT_EQ(sorted_query(bvh.as_query(), lo, hi), sorted_query(brute_force_query(m), lo, hi));
  }
}

}  // namespace
}  // namespace serosa::cutting
