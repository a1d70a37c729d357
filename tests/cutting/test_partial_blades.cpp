// Partial blades (the blade ends inside the mesh): every delta is accepted by engine's apply()
// and passes the invariant checker, whatever the tip does: inside a tet, on a face, on an edge,
// exactly on a node.
#include <gtest/gtest.h>

#include <algorithm>
#include <random>
#include <stdexcept>

#include "cut_helpers.h"
#include "cutting/tet_bvh.h"
#include "mesh_fixtures.h"

namespace serosa::cutting {
namespace {

using testing::cut_and_check;
using testing::problems;

// Cuts, then applies with apply() catching its rejection, then checks the invariants.
::testing::AssertionResult cut_applies_and_checks(const TetMesh& m, const ConvexPolygon& blade,
                                                  TetMesh* out = nullptr,
                                                  const CutOptions& options = {}) {
  const CutResult r = cut_mesh(m, blade, options);
  TetMesh after = m;
  TopologyDelta d = r.delta;
  try {
    apply(after, d);
  } catch (const std::invalid_argument& e) {
    return ::testing::AssertionFailure() << "apply() rejected the delta: " << e.what();
  }
  CutCheckOptions co;
  co.geometry_tol_m = 4.0 * r.stats.tolerance_m + 1e-12;
  co.plane_tol_m = r.stats.tolerance_m;
  const CutCheckReport rep = check_cut(m, after, blade, co);
  if (!rep.ok) return ::testing::AssertionFailure() << problems(rep);
  if (r.stats.degenerate_tets != 0)
    return ::testing::AssertionFailure() << r.stats.degenerate_tets << " degenerate tets";
  if (out) *out = std::move(after);
  return ::testing::AssertionSuccess();
}

TEST(PartialBlades, TipInsideTheMeshGivesAnAcceptedDelta) {
  const double h = 0.01;
  const TetMesh m = test_meshes::kuhn_box(6, 4, 4, 1, h);
  const Vec3 c(3.3 * h, 2 * h, 4 * h);
  const ConvexPolygon blade({c + Vec3(0, -3 * h, h), c + Vec3(0, 3 * h, h),
                             c + Vec3(0, 3 * h, -2 * h), c + Vec3(0, -3 * h, -2 * h)});
  EXPECT_TRUE(cut_applies_and_checks(m, blade));
  // The same blade the other way round; through the BVH the same delta.
  const ConvexPolygon reversed({c + Vec3(0, -3 * h, -2 * h), c + Vec3(0, 3 * h, -2 * h),
                                c + Vec3(0, 3 * h, h), c + Vec3(0, -3 * h, h)});
  EXPECT_TRUE(cut_applies_and_checks(m, reversed));
  const TetBvh bvh(m);
  const CutResult a = cut_mesh(m, blade, {}, bvh.as_query());
  const CutResult b = cut_mesh(m, blade);
  EXPECT_EQ(a.delta.removed_tets, b.delta.removed_tets);
  EXPECT_EQ(a.delta.added_tets, b.delta.added_tets);
  EXPECT_GT(b.stats.tets_partial, 0);
}

// A point of tet `t` of `m` by `kind`: 0 inside, 1 on a face, 2 on an edge, 3 on a node.
Vec3 tip_point(const TetMesh& m, const Tet& t, int kind, std::mt19937& rng) {
  std::uniform_real_distribution<double> u(0.05, 1.0);
  std::array<double, 4> w{u(rng), u(rng), u(rng), u(rng)};
  for (int k = 4 - kind; k < 4; ++k) w[static_cast<std::size_t>(k)] = 0.0;
  if (kind == 3) w = {1.0, 0.0, 0.0, 0.0};
  std::shuffle(w.begin(), w.end(), rng);
  const double sum = w[0] + w[1] + w[2] + w[3];
  Vec3 p = Vec3::Zero();
  for (int k = 0; k < 4; ++k) p += w[static_cast<std::size_t>(k)] / sum * m.x[t[k]];
  return p;
}

// Many random partial blades: a triangle or quad with one corner (the tip) inside a tet, on a
// face, on an edge or exactly on a node, the rest of it reaching out of the mesh or staying
// inside; in random planes and in the grid's own planes (many coplanar nodes). Every delta is
// accepted by apply() and passes the invariant checker, and the mesh stays in one piece.
void random_tips(const CutOptions& options) {
  const double h = 0.01;
  const TetMesh exact = test_meshes::kuhn_box(6, 4, 4, 1, h);
  TetMesh jittered = test_meshes::kuhn_cube(4, h, 0.2, 5);
  std::mt19937 rng(31);
  std::normal_distribution<double> g;
  std::uniform_real_distribution<double> ang(0.0, 6.283185307179586), len(0.5, 6.0);
#if defined(__SANITIZE_ADDRESS__)
  const int cases = 400;
#else
  const int cases = 1200;
#endif
  std::array<int, 4> per_kind{};
  int opened = 0;
  for (int i = 0; i < cases; ++i) {
    const TetMesh& m = i % 3 == 2 ? jittered : exact;
    const int kind = i % 4;
    const Tet& t = m.tets[static_cast<std::size_t>(rng() % m.tets.size())];
    const Vec3 tip = tip_point(m, t, kind, rng);
    Vec3 n(g(rng), g(rng), g(rng));
    if (i % 5 == 0) n = Vec3::Unit(static_cast<int>(rng() % 3));  // the grid's planes
    if (i % 7 == 0) n = Vec3(1, 1, 0).normalized();               // through diagonals
    n.normalize();
    const Vec3 a0 = std::abs(n.x()) < 0.9 ? Vec3::UnitX() : Vec3::UnitY();
    const Vec3 e1 = (a0 - n * n.dot(a0)).normalized(), e2 = n.cross(e1);
    const double phase = ang(rng), spread = 0.3 + 1.2 * (i % 5) / 5.0;
    const double l1 = len(rng) * h, l2 = len(rng) * h;
    std::vector<Vec3> pts{tip};
    pts.push_back(tip + l1 * (std::cos(phase) * e1 + std::sin(phase) * e2));
    if (i % 2 == 1)
      pts.push_back(
          tip + 0.5 * (l1 + l2) *
                    (std::cos(phase + 0.5 * spread) * e1 + std::sin(phase + 0.5 * spread) * e2) /
                    std::cos(0.5 * spread));
    pts.push_back(tip + l2 * (std::cos(phase + spread) * e1 + std::sin(phase + spread) * e2));
    auto blade = ConvexPolygon::make(pts);
    if (!blade) continue;
    TetMesh after;
    ASSERT_TRUE(cut_applies_and_checks(m, *blade, &after, options))
        << "case " << i << " tip kind " << kind << " blade " << blade->points().size();
    EXPECT_EQ(count_components(after), 1) << "case " << i;
    ++per_kind[static_cast<std::size_t>(kind)];
    opened += after.num_tets() > m.num_tets() ? 1 : 0;
  }
  for (int k = 0; k < 4; ++k) EXPECT_GT(per_kind[static_cast<std::size_t>(k)], cases / 8) << k;
  EXPECT_GT(opened, cases / 4);
}

TEST(PartialBlades, RandomTipsGiveAcceptedValidDeltas) { random_tips({}); }

// The same blades with the second pass (CutOptions::reopen_pinned).
TEST(PartialBlades, RandomTipsGiveAcceptedValidDeltasWithTheSecondPass) {
  CutOptions o;
  o.reopen_pinned = true;
  random_tips(o);
}

// Partial blades one after another on the same mesh (each cutting the mesh the previous ones
// made, tips landing on earlier cut points and crack fronts): every delta still applies and
// passes the checker.
void successive_partial_cuts(const CutOptions& options) {
  const double h = 0.01;
  std::mt19937 rng(77);
  std::normal_distribution<double> g;
  std::uniform_real_distribution<double> ang(0.0, 6.283185307179586), len(1.0, 4.0);
#if defined(__SANITIZE_ADDRESS__)
  const int runs = 4;
#else
  const int runs = 12;
#endif
  for (int run = 0; run < runs; ++run) {
    TetMesh m = run % 2 == 0 ? test_meshes::kuhn_box(6, 4, 4, 1, h)
                             : test_meshes::kuhn_cube(4, h, 0.15, run);
    for (int step = 0; step < 8; ++step) {
      const Tet& t = m.tets[static_cast<std::size_t>(rng() % m.tets.size())];
      const Vec3 tip = tip_point(m, t, step % 4, rng);
      Vec3 n = step % 3 == 0 ? Vec3::UnitX() : Vec3(g(rng), g(rng), g(rng)).normalized();
      const Vec3 a0 = std::abs(n.x()) < 0.9 ? Vec3::UnitX() : Vec3::UnitY();
      const Vec3 e1 = (a0 - n * n.dot(a0)).normalized(), e2 = n.cross(e1);
      const double phase = ang(rng);
      auto blade = ConvexPolygon::make(
          {tip, tip + len(rng) * h * (std::cos(phase) * e1 + std::sin(phase) * e2),
           tip + len(rng) * h * (std::cos(phase + 1.0) * e1 + std::sin(phase + 1.0) * e2)});
      if (!blade) continue;
      TetMesh after;
      ASSERT_TRUE(cut_applies_and_checks(m, *blade, &after, options))
          << "run " << run << " step " << step;
      m = std::move(after);
    }
  }
}

TEST(PartialBlades, SuccessivePartialCutsStayValid) { successive_partial_cuts({}); }

TEST(PartialBlades, SuccessivePartialCutsStayValidWithTheSecondPass) {
  CutOptions o;
  o.reopen_pinned = true;
  successive_partial_cuts(o);
}

}  // namespace
}  // namespace serosa::cutting
