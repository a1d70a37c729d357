// cut_mesh: invariants (cutting/validate.h) on every sign case, thousands of random cuts of single
// tets and grids, and the degenerate families: planes through nodes, along edges, in faces,
// axis-aligned through grid nodes, partial, repeated, crossing and near-parallel cuts.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <random>

#include "cut_helpers.h"
#include "cutting/case_table.h"
#include "cutting/section_triangulation.h"
#include "mesh_fixtures.h"

namespace serosa::cutting {
namespace {

using testing::Applied;
using testing::cut_and_check;
using testing::problems;
using testing::square;

// Volume of {phi > 0} in the tets of `m` (x = rest) for the plane (n, d), clipped directly:
// the positive part is a tet, a tet's complement or a prism split into three tets.
double positive_volume_exact(const TetMesh& m, const Vec3& n, double d) {
  double v = 0.0;
  auto vol = [](const Vec3& a, const Vec3& b, const Vec3& c, const Vec3& e) {
    return std::abs(signed_volume(a, b, c, e));
  };
  for (const Tet& t : m.tets) {
    std::vector<Vec3> pos, neg;
    std::vector<double> ppos, pneg;
    for (int k = 0; k < 4; ++k) {
      const double phi = n.dot(m.x[t[k]]) - d;
      (phi > 0.0 ? pos : neg).push_back(m.x[t[k]]);
      (phi > 0.0 ? ppos : pneg).push_back(phi);
    }
    auto cut = [&](std::size_t i, std::size_t j) {  // point on edge pos[i]-neg[j] at phi = 0
      return Vec3(pos[i] + ppos[i] / (ppos[i] - pneg[j]) * (neg[j] - pos[i]));
    };
    const double whole = vol(m.x[t[0]], m.x[t[1]], m.x[t[2]], m.x[t[3]]);
    if (pos.empty()) continue;
    if (neg.empty()) {
      v += whole;
    } else if (pos.size() == 1) {
      v += vol(pos[0], cut(0, 0), cut(0, 1), cut(0, 2));
    } else if (pos.size() == 3) {
      // Complement of the negative corner tet.
      const auto c = [&](std::size_t i) {
        return Vec3(neg[0] + pneg[0] / (pneg[0] - ppos[i]) * (pos[i] - neg[0]));
      };
      v += whole - vol(neg[0], c(0), c(1), c(2));
    } else {
      const Vec3 ac = cut(0, 0), ad = cut(0, 1), bc = cut(1, 0), bd = cut(1, 1);
      v += vol(pos[0], pos[1], ac, ad) + vol(pos[1], ac, ad, bd) + vol(pos[1], ac, bd, bc);
    }
  }
  return v;
}

// Rest volume of the tets whose centroid is on the positive side of (n, d).
double positive_volume_after(const TetMesh& m, const Vec3& n, double d) {
  double v = 0.0;
  for (std::int32_t ti = 0; ti < m.num_tets(); ++ti) {
    const Tet& t = m.tets[ti];
    const Vec3 c = (m.x[t[0]] + m.x[t[1]] + m.x[t[2]] + m.x[t[3]]) / 4.0;
    if (n.dot(c) - d > 0.0) v += m.rest_volume(ti);
  }
  return v;
}

bool has_both_sides(const TetMesh& m, const ConvexPolygon& p, double tol) {
  bool pos = false, neg = false;
  for (const Vec3& x : m.x) {
    pos = pos || p.signed_distance(x) > tol;
    neg = neg || p.signed_distance(x) < -tol;
  }
  return pos && neg;
}

// A tet whose node k lies at height sign_k * (0.4 + 0.2 k) over the plane z = 0.
TetMesh tet_for_code(int code) {
  const std::array<Sign, 4> s = signs_of_code(code);
  const std::array<Vec3, 4> xy{Vec3(-0.6, -0.4, 0), Vec3(0.9, -0.3, 0), Vec3(0.1, 0.8, 0),
                               Vec3(0.2, 0.1, 0)};
  TetMesh m;
  for (int k = 0; k < 4; ++k)
    m.add_node(xy[k] + Vec3(0, 0, static_cast<double>(s[k]) * (0.4 + 0.2 * k)));
  if (signed_volume(m.rest[0], m.rest[1], m.rest[2], m.rest[3]) < 0.0)
    for (Vec3& p : m.rest) p.x() = -p.x();  // mirror: orientation flips, signs stay
  m.fill_node_state();
  for (int k = 0; k < 4; ++k) m.x[k] = m.rest[k];
  m.add_tet({0, 1, 2, 3}, 1);
  return m;
}

TEST(CutMesh, EverySignCaseAndPlacement) {
  int checked = 0;
  for (int code = 0; code < 81; ++code) {
    if (case_table()[code].canonical == CanonicalCase::kDegenerate) continue;  // flat: no tet
    const TetMesh m = tet_for_code(code);
    ASSERT_GT(m.rest_volume(0), 1e-3) << code;
    const Vec3 n = Vec3::UnitZ();
    const std::array<Sign, 4> s = signs_of_code(code);
    const bool crosses = std::count(s.begin(), s.end(), Sign::kPos) > 0 &&
                         std::count(s.begin(), s.end(), Sign::kNeg) > 0;
    // Covering: a complete cut.
    {
      const Applied a = cut_and_check(m, square(n, Vec3::Zero(), 10.0), true);
      EXPECT_TRUE(a.report.ok) << "code " << code << "\n" << problems(a.report);
      EXPECT_EQ(a.result.stats.degenerate_tets, 0);
      EXPECT_EQ(a.result.stats.tets_split, crosses ? 1 : 0) << code;
      EXPECT_EQ(count_components(a.after), crosses ? 2 : 1) << code;
      ++checked;
    }
    // Partial placements: half-covering, an edge through each node, a corner on each node.
    std::vector<ConvexPolygon> blades;
    blades.push_back(
        ConvexPolygon({Vec3(0.3, -5, 0), Vec3(5, -5, 0), Vec3(5, 5, 0), Vec3(0.3, 5, 0)}));
    for (int k = 0; k < 4; ++k) {
      const Vec3 p(m.x[k].x(), m.x[k].y(), 0.0);
      blades.push_back(ConvexPolygon(
          {p + Vec3(0, -5, 0), p + Vec3(5, -5, 0), p + Vec3(5, 5, 0), p + Vec3(0, 5, 0)}));
      blades.push_back(ConvexPolygon({p, p + Vec3(3, 0.2, 0), p + Vec3(0.3, 3, 0)}));
    }
    for (int i = 0; i < 4; ++i)
      for (int j = i + 1; j < 4; ++j) {  // an edge along the projection of each tet edge
        const Vec3 a(m.x[i].x(), m.x[i].y(), 0.0), b(m.x[j].x(), m.x[j].y(), 0.0);
        if ((b - a).norm() < 1e-9) continue;
        const Vec3 side = Vec3::UnitZ().cross(b - a).normalized() * 4.0;
        blades.push_back(ConvexPolygon({a, b, b + side, a + side}));
      }
    for (const ConvexPolygon& blade : blades) {
      const Applied a = cut_and_check(m, blade);
      EXPECT_TRUE(a.report.ok) << "code " << code << "\n" << problems(a.report);
      EXPECT_EQ(a.result.stats.degenerate_tets, 0);
      ++checked;
    }
  }
  EXPECT_GT(checked, 80 * 10);
}

TEST(CutMesh, RandomPlanesThroughSingleTets) {
  std::mt19937 rng(11);
  std::normal_distribution<double> g;
  std::uniform_real_distribution<double> u(0.0, 1.0);
  int split = 0;
  for (int i = 0; i < 3000; ++i) {
    const TetMesh m = fixtures::random_tet(rng);
    // A point inside the tet, or (every fourth case) a node, or a point on an edge.
    std::array<double, 4> w{u(rng), u(rng), u(rng), u(rng)};
    if (i % 4 == 1) w = {1, 0, 0, 0};
    if (i % 4 == 2) w = {u(rng), 1, 0, 0};
    const double ws = w[0] + w[1] + w[2] + w[3];
    Vec3 c = Vec3::Zero();
    for (int k = 0; k < 4; ++k) c += w[k] / ws * m.x[k];
    Vec3 n(g(rng), g(rng), g(rng));
    if (i % 8 == 3) n = (m.x[1] - m.x[0]).cross(m.x[2] - m.x[0]);               // in a face's plane
    if (i % 8 == 5) n = (m.x[1] - m.x[0]).cross(Vec3(g(rng), g(rng), g(rng)));  // along edge 01
    if (i % 8 == 5) c = m.x[0];
    const ConvexPolygon blade = square(n, c, 10.0, u(rng));
    const Applied a = cut_and_check(m, blade, true);
    ASSERT_TRUE(a.report.ok) << "case " << i << "\n" << problems(a.report);
    ASSERT_EQ(a.result.stats.degenerate_tets, 0);
    const bool both = has_both_sides(m, blade, a.result.stats.tolerance_m);
    EXPECT_EQ(count_components(a.after), both ? 2 : 1) << i;
    split += a.result.stats.tets_split > 0 ? 1 : 0;
  }
  EXPECT_GT(split, 1500);
}

// A complete cut of a grid: invariants, separation in two pieces, and the positive side's volume
// equal to the exact clipped volume.
void check_through_cut(const TetMesh& m, const Vec3& n, const Vec3& c, double exact_tol,
                       const std::string& what) {
  const ConvexPolygon blade = square(n, c, 100.0, 0.3);
  const Applied a = cut_and_check(m, blade, true);
  ASSERT_TRUE(a.report.ok) << what << "\n" << problems(a.report);
  ASSERT_EQ(a.result.stats.degenerate_tets, 0) << what;
  if (!has_both_sides(m, blade, a.result.stats.tolerance_m)) return;
  EXPECT_EQ(count_components(a.after), 2) << what;
  const double d = blade.offset();
  const double exact = positive_volume_exact(m, blade.normal(), d);
  EXPECT_NEAR(positive_volume_after(a.after, blade.normal(), d), exact, exact_tol) << what;
}

TEST(CutMesh, AxisAlignedPlanesThroughGridNodes) {
  const TetMesh m = test_meshes::kuhn_cube(4);
  for (int axis = 0; axis < 3; ++axis)
    for (double off : {1.0, 2.0, 3.0, 1.5, 2.25}) {
      Vec3 n = Vec3::Zero();
      n[axis] = axis == 1 ? -1.0 : 1.0;
      Vec3 c = Vec3::Constant(2.0);
      c[axis] = off;
      const ConvexPolygon blade = square(n, c, 100.0);
      const Applied a = cut_and_check(m, blade, true);
      ASSERT_TRUE(a.report.ok) << axis << " " << off << "\n" << problems(a.report);
      EXPECT_EQ(count_components(a.after), 2);
      // The positive side holds exactly its share of the cube.
      const double pos = positive_volume_after(a.after, blade.normal(), blade.offset());
      const double share = n[axis] > 0 ? (4.0 - off) / 4.0 : off / 4.0;
      EXPECT_NEAR(pos, 64.0 * share, 1e-12);
    }
}

TEST(CutMesh, DiagonalPlanesThroughGridNodes) {
  const TetMesh m = test_meshes::kuhn_cube(4);
  const std::vector<Vec3> normals{Vec3(1, 1, 0),  Vec3(1, -1, 0), Vec3(1, 1, 1), Vec3(1, -1, 2),
                                  Vec3(0, 1, -1), Vec3(2, 1, 0),  Vec3(1, 2, 3)};
  for (const Vec3& n : normals)
    for (const Vec3& c : {Vec3(2, 2, 2), Vec3(1, 2, 3), Vec3(3, 1, 1), Vec3(0, 0, 0)})
      check_through_cut(
          m, n, c, 1e-9,
          "n " + std::to_string(n.x()) + std::to_string(n.y()) + std::to_string(n.z()));
}

TEST(CutMesh, RandomPlanesThroughGrids) {
  std::mt19937 rng(5);
  std::normal_distribution<double> g;
  std::uniform_real_distribution<double> u(0.0, 3.0);
  const TetMesh exact = test_meshes::kuhn_cube(3);
  const TetMesh jittered = test_meshes::kuhn_cube(3, 1.0, 0.2, 9);
  for (int i = 0; i < 400; ++i) {
    const TetMesh& m = i % 2 == 0 ? exact : jittered;
    const Vec3 n(g(rng), g(rng), g(rng));
    const Vec3 c(u(rng), u(rng), u(rng));
    check_through_cut(m, n, c, 1e-6, "case " + std::to_string(i));
    if (::testing::Test::HasFatalFailure()) return;
  }
}

TEST(CutMesh, PartialCutsStayWelded) {
  std::mt19937 rng(3);
  std::normal_distribution<double> g;
  std::uniform_real_distribution<double> u(0.5, 3.5);
  std::uniform_real_distribution<double> s(0.2, 3.0);
  const TetMesh m = test_meshes::kuhn_cube(4);
  int opened = 0, partial = 0;
  for (int i = 0; i < 300; ++i) {
    Vec3 n(g(rng), g(rng), g(rng));
    if (i % 3 == 0) n = Vec3::UnitZ();  // in the grid's planes: many coplanar nodes
    const Vec3 c = i % 3 == 0 ? Vec3(u(rng), u(rng), 2.0) : Vec3(u(rng), u(rng), u(rng));
    // A small polygon ending inside the mesh; every fifth has its tip exactly on a grid node.
    std::vector<Vec3> pts{c, c + s(rng) * Vec3(1, 0.1, 0), c + s(rng) * Vec3(0.2, 1, 0)};
    if (i % 5 == 0) pts[0] = Vec3(2, 2, 2);
    const Vec3 e1 = pts[1] - pts[0], e2 = pts[2] - pts[0];
    if (i % 3 != 0) {  // tilt into the plane with normal n
      const Vec3 nn = n.normalized();
      pts[1] = pts[0] + e1 - nn * nn.dot(e1);
      pts[2] = pts[0] + e2 - nn * nn.dot(e2);
    }
    auto blade = ConvexPolygon::make(pts);
    if (!blade) continue;
    const Applied a = cut_and_check(m, *blade);
    ASSERT_TRUE(a.report.ok) << "case " << i << "\n" << problems(a.report);
    EXPECT_EQ(count_components(a.after), 1) << "a partial cut must not cut a piece off";
    opened += a.report.boundary_faces_on_blade > 0 ? 1 : 0;
    partial += a.result.stats.tets_partial > 0 ? 1 : 0;
  }
  EXPECT_GT(opened, 10);
  EXPECT_GT(partial, 100);
}

TEST(CutMesh, HalfCoveringBladeOpensACrackAndStaysConnected) {
  const TetMesh m = test_meshes::kuhn_cube(4);
  // The blade covers x < 2.5 of the section z = 1.5: the crack opens there and stops.
  const ConvexPolygon blade(
      {Vec3(-1, -1, 1.5), Vec3(2.5, -1, 1.5), Vec3(2.5, 5, 1.5), Vec3(-1, 5, 1.5)});
  const Applied a = cut_and_check(m, blade);
  ASSERT_TRUE(a.report.ok) << problems(a.report);
  EXPECT_EQ(count_components(a.after), 1);
  // At least the first column of cubes (x in [0, 1]) is fully opened: 2 faces per unit square
  // on each side.
  EXPECT_GE(a.report.boundary_faces_on_blade, 2 * 2 * 4);
  EXPECT_GT(a.result.stats.tets_partial, 0);
}

TEST(CutMesh, RepeatedCrossingAndNearParallelCuts) {
  std::mt19937 rng(21);
  std::normal_distribution<double> g;
  std::uniform_real_distribution<double> u(0.5, 2.5);
  for (int run = 0; run < 20; ++run) {
    TetMesh m = test_meshes::kuhn_cube(3, 1.0, run % 2 == 0 ? 0.0 : 0.15, 40 + run);
    Vec3 last_n = Vec3::UnitZ(), last_c = Vec3::Constant(1.5);
    for (int step = 0; step < 6; ++step) {
      Vec3 n(g(rng), g(rng), g(rng));
      Vec3 c(u(rng), u(rng), u(rng));
      if (step % 3 == 1) {  // the same plane again
        n = last_n;
        c = last_c;
      } else if (step % 3 == 2) {  // near-parallel: 1e-6 of the mesh size away
        n = last_n;
        c = last_c + 1e-6 * last_n.normalized();
      }
      last_n = n;
      last_c = c;
      const bool full = step % 2 == 0;
      const ConvexPolygon blade = square(n, c, full ? 100.0 : 0.8, 0.1 * step);
      const Applied a = cut_and_check(m, blade, full);
      ASSERT_TRUE(a.report.ok) << "run " << run << " step " << step << "\n" << problems(a.report);
      ASSERT_EQ(a.result.stats.degenerate_tets, 0);
      m = a.after;
    }
  }
}

TEST(CutMesh, DeltaIsDeterministicAndLocal) {
  const TetMesh m = test_meshes::kuhn_cube(4);
  const ConvexPolygon blade = square(Vec3(0.3, 1, 0.2), Vec3(2, 2.1, 2), 100.0);
  const CutResult a = cut_mesh(m, blade);
  const CutResult b = cut_mesh(m, blade);
  EXPECT_EQ(a.delta.removed_tets, b.delta.removed_tets);
  EXPECT_EQ(a.delta.added_tets, b.delta.added_tets);
  EXPECT_EQ(a.delta.added_nodes.size(), b.delta.added_nodes.size());
  // Existing nodes never move: apply only appends.
  TetMesh after = m;
  TopologyDelta d = a.delta;
  apply(after, d);
  for (std::int32_t i = 0; i < m.num_nodes(); ++i) EXPECT_EQ(after.rest[i], m.rest[i]);
  // Stats add up: cut points come in pairs.
  const CutStats& st = a.stats;
  EXPECT_EQ(st.nodes_added,
            2 * st.edge_pairs + st.edge_singles + st.clones + st.steiner_points + st.face_points);
  EXPECT_EQ(st.tets_removed,
            st.tets_split + st.tets_relabelled + st.tets_partial + st.second_pass_originals);
  EXPECT_EQ(st.tets_added, static_cast<std::int64_t>(a.delta.added_tets.size()));
  EXPECT_GT(st.tets_split, 0);
  // A small blade touches a few tets only.
  const CutResult small = cut_mesh(m, square(Vec3(0.3, 1, 0.2), Vec3(2, 2.1, 2), 0.6));
  EXPECT_LT(small.stats.candidates, m.num_tets() / 4);
  EXPECT_GT(small.stats.tets_removed, 0);
}

}  // namespace
}  // namespace serosa::cutting

namespace serosa::cutting {
namespace {

// Growth per cut is bounded by the patterns (a complete tet gives at most 6 tets: two prisms of
// three; a relabelled tet 1; a partial tet at most 12: four faces of at most three triangles,
// coned), and the numbers are reported: tets created per cut and minimum quality after it.
void growth_is_bounded_and_reported(const CutOptions& options) {
  std::mt19937 rng(17);
  std::normal_distribution<double> g;
  std::uniform_real_distribution<double> u(0.5, 3.5);
  const TetMesh m = test_meshes::kuhn_cube(4, 1.0, 0.15, 12);
  std::int64_t max_added = 0, total_added = 0;
  double min_quality = 1.0;
  for (int i = 0; i < 100; ++i) {
    const ConvexPolygon blade = testing::square(Vec3(g(rng), g(rng), g(rng)),
                                                Vec3(u(rng), u(rng), u(rng)), i % 2 ? 100.0 : 1.0);
    const testing::Applied a = testing::cut_and_check(m, blade, i % 2 == 1, options);
    ASSERT_TRUE(a.report.ok) << testing::problems(a.report);
    const CutStats& st = a.result.stats;
    EXPECT_EQ(st.second_pass_failed, 0);
    EXPECT_LE(st.tets_added, 6 * st.tets_split + st.tets_relabelled + 12 * st.tets_partial +
                                 12 * st.second_pass_tets);
    max_added = std::max(max_added, st.tets_added - st.tets_removed);
    total_added += st.tets_added - st.tets_removed;
    min_quality = std::min(min_quality, a.report.min_quality);
  }
  ::testing::Test::RecordProperty("max_net_tets_per_cut", static_cast<int>(max_added));
  ::testing::Test::RecordProperty("mean_net_tets_per_cut", static_cast<int>(total_added / 100));
  ::testing::Test::RecordProperty("min_quality_x1e6", static_cast<int>(min_quality * 1e6));
  std::printf(
      "grid 4^3 (384 tets), 100 cuts%s: net tets per cut max %lld mean %lld; min quality %g\n",
      options.reopen_pinned ? " (second pass)" : "", static_cast<long long>(max_added),
      static_cast<long long>(total_added / 100), min_quality);
  EXPECT_GT(min_quality, 0.0);
}

TEST(CutMesh, GrowthIsBoundedAndReported) { growth_is_bounded_and_reported({}); }

TEST(CutMesh, GrowthIsBoundedAndReportedWithTheSecondPass) {
  CutOptions o;
  o.reopen_pinned = true;
  growth_is_bounded_and_reported(o);
}

}  // namespace
}  // namespace serosa::cutting

namespace serosa::cutting {
namespace {

// What 200 random partial blades about a tet wide opened (PartialCrack tests below).
struct Coverage {
  int cases = 0, exact_cases = 0, flagged_cases = 0;
  int covered_cases = 0;  ///< not pinned, and some tet lies wholly under the blade
  double min_opened = 1.0, sum_opened = 0.0, sum_short = 0.0;  // crack area / twice the blade's
  [[nodiscard]] int short_cases() const { return cases - exact_cases; }
  [[nodiscard]] double mean_opened() const { return cases > 0 ? sum_opened / cases : 1.0; }
  [[nodiscard]] double mean_short() const {  // over the cases that are not exact
    return short_cases() > 0 ? sum_short / short_cases() : 1.0;
  }
};

// Area (m^2) of the blade's plane inside the tets whose section lies wholly and strictly inside
// the blade (no node within 1e-9 m of the plane, every corner of the section inside the blade
// by more than 1e-9 m): the part of the blade that no outline crosses. The crack must cover at
// least this much: it stops only in the tets the blade's outline crosses.
double fully_covered_area(const TetMesh& m, const ConvexPolygon& blade) {
  constexpr double kMargin = 1e-9;
  constexpr std::array<std::array<int, 2>, 6> kEdges{
      {{0, 1}, {0, 2}, {0, 3}, {1, 2}, {1, 3}, {2, 3}}};
  double total = 0.0;
  for (const Tet& t : m.tets) {
    std::array<double, 4> phi{};
    bool near = false;
    for (int k = 0; k < 4; ++k) {
      phi[static_cast<std::size_t>(k)] =
          blade.signed_distance(m.x[static_cast<std::size_t>(t[static_cast<std::size_t>(k)])]);
      near = near || std::abs(phi[static_cast<std::size_t>(k)]) < kMargin;
    }
    if (near) continue;
    std::vector<Eigen::Vector2d> pts;
    bool inside = true;
    for (const auto& e : kEdges) {
      const double pa = phi[static_cast<std::size_t>(e[0])],
                   pb = phi[static_cast<std::size_t>(e[1])];
      if ((pa > 0.0) == (pb > 0.0)) continue;
      const Vec3& xa = m.x[static_cast<std::size_t>(t[static_cast<std::size_t>(e[0])])];
      const Vec3& xb = m.x[static_cast<std::size_t>(t[static_cast<std::size_t>(e[1])])];
      const Vec3 p = xa + (pa / (pa - pb)) * (xb - xa);
      inside = inside && blade.inside_margin(p) > kMargin;
      pts.push_back(blade.to_plane(p));
    }
    if (pts.size() < 3 || !inside) continue;
    Eigen::Vector2d c = Eigen::Vector2d::Zero();
    for (const auto& p : pts) c += p / static_cast<double>(pts.size());
    std::sort(pts.begin(), pts.end(), [&](const Eigen::Vector2d& a, const Eigen::Vector2d& b) {
      return std::atan2(a.y() - c.y(), a.x() - c.x()) < std::atan2(b.y() - c.y(), b.x() - c.x());
    });
    for (std::size_t k = 0; k < pts.size(); ++k)
      total += std::abs(area2d(c, pts[k], pts[(k + 1) % pts.size()]));
  }
  return total;
}

// Partial cuts open the blade's area: the crack's two sides together cover twice the part of
// the section the blade covers, whatever the blade's outline does inside the tets (crossing faces
// without cutting edges, corners inside tets, tips on nodes). Where a tet's crack cannot cover
// its part (tets_pinned: S without area holding a corner strictly inside, or a sliver section;
// tets_short: no apex touches every front side, or no point of the part opens), the cut is
// flagged; every cut not flagged must open exactly the blade's area. Every cut with no pin must
// open at least the blade's part of the tets it covers wholly. The share of the blade the crack
// covers is measured and reported.
Coverage partial_crack(const CutOptions& options, double radius_m = 0.3) {
  // "Exactly": to 1e-5 of the blade's area. A tet whose part under the blade is thinner than
  // the classification tolerance (1e-6 of the edge length) is grazed, not opened.
  constexpr double kExact = 1e-5;
  Coverage cov;
  std::mt19937 rng(8);
  std::uniform_real_distribution<double> u(0.3, 3.7);
  std::uniform_real_distribution<double> ang(0.0, 6.283185307179586);
  std::normal_distribution<double> g;
  const TetMesh exact = test_meshes::kuhn_cube(4);
  const TetMesh jittered = test_meshes::kuhn_cube(4, 1.0, 0.2, 3);
  for (int i = 0; i < 200; ++i) {
    const TetMesh& m = i % 2 == 0 ? exact : jittered;
    // A blade inside the cube: a triangle or a quad in a random (or axis) plane.
    Vec3 n(g(rng), g(rng), g(rng));
    if (i % 5 == 0) n = Vec3::UnitZ();
    n.normalize();
    Vec3 c(u(rng), u(rng), u(rng));
    const Vec3 a0 = std::abs(n.x()) < 0.9 ? Vec3::UnitX() : Vec3::UnitY();
    const Vec3 e1 = (a0 - n * n.dot(a0)).normalized(), e2 = n.cross(e1);
    const int k = 3 + i % 2;
    const double r = radius_m * (1.0 + (i % 7) / 6.0), phase = ang(rng);
    // Larger blades: the centre drawn where the blade fits in the cube.
    if (radius_m > 0.3)
      c = Vec3::Constant(2.0) + std::max(0.0, (1.9 - r) / 1.7) * (c - Vec3::Constant(2.0));
    std::vector<Vec3> pts;
    for (int j = 0; j < k; ++j) {
      const double t = phase + 6.283185307179586 * j / k;
      pts.push_back(c + r * (std::cos(t) * e1 + std::sin(t) * e2));
    }
    if (i % 7 == 3) pts[0] = Vec3(2, 2, 2) + 0.0 * n;  // a corner exactly on a grid node
    auto blade = ConvexPolygon::make(pts);
    if (!blade) continue;
    bool in_cube = true;
    for (const Vec3& p : blade->points())
      in_cube = in_cube && (p.array() > 0.05).all() && (p.array() < 3.95).all();
    if (!in_cube) continue;
    const Applied a = cut_and_check(m, *blade, false, options);
    EXPECT_TRUE(a.report.ok) << "case " << i << "\n" << problems(a.report);
    EXPECT_EQ(a.result.stats.degenerate_tets, 0) << i;
    EXPECT_EQ(a.result.stats.second_pass_failed, 0) << i;
    EXPECT_EQ(count_components(a.after), 1) << i;
    const double opened = a.report.blade_face_area_m2 / (2.0 * blade->area());
    EXPECT_LE(opened, 1.0 + 1e-9) << i;
    // The crack reaches every tet the blade covers wholly (pins weld their neighbours' edges).
    if (a.result.stats.tets_pinned == 0) {
      const double covered = fully_covered_area(m, *blade);
      EXPECT_GE(opened * blade->area(), covered * (1.0 - 1e-9)) << i;
      cov.covered_cases += covered > 0.0 ? 1 : 0;
    }
    const bool flagged = a.result.stats.tets_pinned > 0 || a.result.stats.tets_short > 0;
    if (!flagged) {
      EXPECT_NEAR(opened, 1.0, kExact) << i;
    }
    ++cov.cases;
    cov.flagged_cases += flagged ? 1 : 0;
    cov.sum_opened += opened;
    cov.min_opened = std::min(cov.min_opened, opened);
    if (std::abs(opened - 1.0) <= kExact) {
      ++cov.exact_cases;
    } else {
      cov.sum_short += opened;
    }
  }
  std::printf(
      "partial blades %.2f-%.2f m across inside a 4^3 grid%s: %d cuts, %d opened exactly (%d "
      "flagged); the crack covers %.3f of the blade's area on average, %.3f over the other %d, "
      "%.3f at the least; %d reach tets the blade covers wholly\n",
      2.0 * radius_m, 4.0 * radius_m, options.reopen_pinned ? " (second pass)" : "", cov.cases,
      cov.exact_cases, cov.flagged_cases, cov.mean_opened(), cov.mean_short(), cov.short_cases(),
      cov.min_opened, cov.covered_cases);
  return cov;
}

TEST(CutMesh, PartialCrackOfSmallBladesIsExactUnlessFlagged) {
  const Coverage cov = partial_crack({});
  // Blades about a tet wide: many have two corners in one tet or pass through one as a strip,
  // or cut no edge strictly inside (nothing on their outline can open in one pass). Both kinds
  // must occur here, and the exact ones must be many.
  EXPECT_GT(cov.exact_cases, 20);
  EXPECT_GT(cov.short_cases(), 0);
}

// The second pass (CutOptions::reopen_pinned) cuts the tets no single apex opens fully again,
// from a point inside the blade's part of their section: every invariant still holds, the
// exact cases stay exact, and most cuts open exactly (docs/BENCHMARKS.md "Cutting").
TEST(CutMesh, PartialCrackWithTheSecondPassCoversMostOfTheBlade) {
  const Coverage one = partial_crack({});
  CutOptions o;
  o.reopen_pinned = true;
  const Coverage two = partial_crack(o);
  EXPECT_GE(two.exact_cases, one.exact_cases);
  EXPECT_GT(two.mean_opened(), 0.9);
  EXPECT_GT(two.mean_opened(), one.mean_opened() + 0.2);
}

// Blades two to four cells across: their outline crosses many tets, and every tet they cover
// wholly opens (checked in partial_crack); the crack covers nearly all of the blade.
TEST(CutMesh, PartialCrackOfLargerBladesStopsOnlyInTheTetsTheOutlineCrosses) {
  const Coverage cov = partial_crack({}, 1.0);
  EXPECT_GT(cov.cases, 100);
  EXPECT_GT(cov.covered_cases, 50);
  EXPECT_GT(cov.mean_opened(), 0.9);
  CutOptions o;
  o.reopen_pinned = true;
  const Coverage two = partial_crack(o, 1.0);
  EXPECT_GT(two.mean_opened(), 0.95);
}

TEST(CutMesh, HalfCoveringBladeOpensExactlyItsPart) {
  const TetMesh m = test_meshes::kuhn_cube(4);
  for (double edge_x : {2.5, 2.0, 1.3}) {
    const ConvexPolygon blade(
        {Vec3(-1, -1, 1.5), Vec3(edge_x, -1, 1.5), Vec3(edge_x, 5, 1.5), Vec3(-1, 5, 1.5)});
    const Applied a = cut_and_check(m, blade);
    ASSERT_TRUE(a.report.ok) << problems(a.report);
    EXPECT_EQ(count_components(a.after), 1);
    EXPECT_NEAR(a.report.blade_face_area_m2, 2.0 * 4.0 * edge_x, 1e-9) << edge_x;
    // Slanted outline: crosses faces without cutting their edges.
    const ConvexPolygon slanted(
        {Vec3(-1, -1, 1.5), Vec3(edge_x, -1, 1.5), Vec3(edge_x + 0.7, 5, 1.5), Vec3(-1, 5, 1.5)});
    const Applied b = cut_and_check(m, slanted);
    ASSERT_TRUE(b.report.ok) << problems(b.report);
    EXPECT_EQ(b.result.stats.tets_pinned, 0);
    // The mesh spans y in [0, 4]: the outline's x at y is edge_x + 0.7 (y + 1) / 6.
    const double x0 = edge_x + 0.7 / 6.0, x4 = edge_x + 0.7 * 5.0 / 6.0;
    EXPECT_NEAR(b.report.blade_face_area_m2, 2.0 * 4.0 * 0.5 * (x0 + x4), 1e-9) << edge_x;
  }
}

// The plane x + y = 2 holds vertical grid edges, and the Kuhn tets around them straddle it with
// two nodes on it: the blade's outline z = zc crosses those coplanar edges. The crossings become
// welded nodes on the edges (every tet around an edge shares them), so the crack stops exactly
// on the outline: its area is the blade's part of the section, 2 sqrt(2) zc, on each side.
TEST(CutMesh, OutlineAcrossCoplanarEdgesStopsTheCrackExactlyThere) {
  for (const bool slanted : {false, true}) {
    const TetMesh m = test_meshes::kuhn_cube(4);
    for (const double zc : {0.5, 1.3, 2.75}) {
      // The outline from (3, -1, zc - d) to (-1, 3, zc + d): z = zc - d/10 ... zc + d/10 over the
      // section, zc on average.
      const double d = slanted ? 0.2 : 0.0;
      const ConvexPolygon blade(
          {Vec3(-1, 3, -1), Vec3(3, -1, -1), Vec3(3, -1, zc - d), Vec3(-1, 3, zc + d)});
      const Applied a = cut_and_check(m, blade);
      ASSERT_TRUE(a.report.ok) << problems(a.report);
      EXPECT_EQ(a.result.stats.tets_pinned, 0) << zc;
      EXPECT_EQ(a.result.stats.tets_short, 0) << zc;
      EXPECT_GT(a.result.stats.face_points, 0) << zc;  // the crossings of the coplanar edges
      EXPECT_EQ(count_components(a.after), 1) << zc;
      // The section x + y = 2 inside the cube: s = (x - y) / sqrt(2) in [-sqrt(2), sqrt(2)], z
      // in [0, 4]; the blade covers z up to the outline (linear in s when slanted).
      const double expect = 2.0 * std::sqrt(2.0) * zc;
      EXPECT_NEAR(a.report.blade_face_area_m2, 2.0 * expect, 1e-9) << zc << " " << slanted;
    }
  }
}

}  // namespace
}  // namespace serosa::cutting
