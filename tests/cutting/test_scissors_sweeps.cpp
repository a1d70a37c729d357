// A scissors closing over a beam as many small per-step sweeps (issue 3, partial cuts): each
// step's polygon is a thin triangle from the hinge sharing its trailing edge with the previous
// step's leading edge, so every step cuts the mesh the previous steps made, along their crack
// front. The crack stops where the blade ends, but tets the blade has crossed open: at the end
// the beam is in two pieces, one on each side, with volume conserved, and every intermediate
// mesh passes the invariant checker.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <random>
#include <stdexcept>
#include <unordered_set>

#include "cut_helpers.h"
#include "cutting/weld_map.h"
#include "mesh_fixtures.h"

namespace serosa::cutting {
namespace {

using testing::problems;

struct SweepRun {
  TetMesh mesh;
  int steps_done = 0;
  std::int64_t pinned = 0;
  std::string failure;
};

// A scissors blade hinged at `hinge`, rotating in the plane through it with unit normal n (in-
// plane axes e1, e2) from angle a0 to a1 (rad) in `steps` steps; each step's polygon is the
// triangle (hinge, tip before, tip after), cut and checked in turn.
SweepRun scissors(const TetMesh& beam, const Vec3& hinge, const Vec3& n, double length, double a0,
                  double a1, int steps) {
  SweepRun run{beam, 0, 0, {}};
  const Vec3 a = n.unitOrthogonal(), b = n.cross(a);
  auto tip = [&](double t) -> Vec3 { return hinge + length * (std::cos(t) * a + std::sin(t) * b); };
  for (int k = 0; k < steps; ++k) {
    const double s0 = a0 + (a1 - a0) * k / steps, s1 = a0 + (a1 - a0) * (k + 1) / steps;
    auto blade = ConvexPolygon::make({hinge, tip(s0), tip(s1)});
    if (!blade) continue;
    const CutResult r = cut_mesh(run.mesh, *blade);
    TetMesh after = run.mesh;
    TopologyDelta d = r.delta;
    try {
      apply(after, d);
    } catch (const std::invalid_argument& e) {
      run.failure = "step " + std::to_string(k) + ": apply() rejected: " + e.what();
      return run;
    }
    CutCheckOptions co;
    co.geometry_tol_m = 4.0 * r.stats.tolerance_m + 1e-12;
    co.plane_tol_m = r.stats.tolerance_m;
    const CutCheckReport rep = check_cut(run.mesh, after, *blade, co);
    if (!rep.ok || r.stats.degenerate_tets != 0) {
      run.failure = "step " + std::to_string(k) + ": " + problems(rep);
      return run;
    }
    run.pinned += r.stats.tets_pinned;
    run.mesh = std::move(after);
    ++run.steps_done;
  }
  return run;
}

// The beam is in two pieces, each on one side of the plane (n, hinge) within tol, and the
// positive piece has the exact clipped volume of the beam before.
void expect_cut_through(const TetMesh& before, const SweepRun& run, const Vec3& n,
                        const Vec3& hinge, double tol, const std::string& what) {
  ASSERT_TRUE(run.failure.empty()) << what << ": " << run.failure;
  const TetMesh& m = run.mesh;
  ASSERT_EQ(count_components(m), 2) << what << " (pinned tets " << run.pinned << ")";
  const std::vector<std::int32_t> comp = tet_components(m);
  const double d = n.dot(hinge);
  std::array<double, 2> lo{1e300, 1e300}, hi{-1e300, -1e300}, vol{0.0, 0.0};
  for (std::int32_t t = 0; t < m.num_tets(); ++t) {
    const auto c = static_cast<std::size_t>(comp[static_cast<std::size_t>(t)]);
    vol[c] += m.rest_volume(t);
    for (std::int32_t v : m.tets[static_cast<std::size_t>(t)]) {
      const double phi = n.dot(m.x[static_cast<std::size_t>(v)]) - d;
      lo[c] = std::min(lo[c], phi);
      hi[c] = std::max(hi[c], phi);
    }
  }
  const std::size_t p = lo[0] >= -tol ? 0 : 1;  // the positive piece
  EXPECT_GE(lo[p], -tol) << what;
  EXPECT_LE(hi[1 - p], tol) << what;
  double total = 0.0;
  for (std::int32_t t = 0; t < before.num_tets(); ++t) total += before.rest_volume(t);
  EXPECT_NEAR(vol[0] + vol[1], total, 1e-12 * total) << what;
  EXPECT_NEAR(vol[p], clipped_positive_volume(before, n, d, tol), 1e-10 * total) << what;
}

// Planes that cross the beam's tets (no coplanar grid faces): straight, tilted, and through a
// jittered beam. 2, 4 and 20 steps each.
TEST(ScissorsSweeps, SmallStepsCutABeamThrough) {
  const double h = 0.01;
  const TetMesh beam = fixtures::box(8, 2, 2, 1, h);
  TetMesh jittered = fixtures::box(8, 2, 2, 1, h);
  {
    std::mt19937 rng(3);
    std::uniform_real_distribution<double> u(-0.2 * h, 0.2 * h);
    for (std::size_t i = 0; i < jittered.x.size(); ++i) {
      const Vec3& p = jittered.rest[i];
      if (p.x() > 0.5 * h && p.x() < 7.5 * h) jittered.rest[i].x() += u(rng);  // keep the ends
      jittered.x[i] = jittered.rest[i];
    }
  }
  // Hinge beside the beam; the blade (5h long) closes from above it (80 deg) to below (-80).
  const double a0 = 80.0 * 3.141592653589793 / 180.0, a1 = -a0;
  struct Case {
    const TetMesh* mesh;
    Vec3 hinge, n;
    const char* name;
  };
  const std::vector<Case> cases{
      {&beam, Vec3(3.37 * h, -h, h), Vec3::UnitX(), "x = 3.37h"},
      {&beam, Vec3(4.5 * h, -h, h), Vec3(1.0, 0.15, -0.1).normalized(), "tilted"},
      {&jittered, Vec3(4.0 * h, -h, h), Vec3::UnitX(), "jittered beam, x = 4h"},
  };
  for (const Case& c : cases)
    for (int steps : {2, 4, 20}) {
      if (c.mesh == &beam && c.n != Vec3::UnitX() && steps == 20) continue;  // own test below
      const SweepRun run = scissors(*c.mesh, c.hinge, c.n, 5.0 * h, a0, a1, steps);
      const std::string what = std::string(c.name) + ", " + std::to_string(steps) + " steps";
      std::printf("scissors %s: %d tets, pinned %lld, pieces %d\n", what.c_str(),
                  run.mesh.num_tets(), static_cast<long long>(run.pinned),
                  count_components(run.mesh));
      expect_cut_through(*c.mesh, run, c.n, c.hinge, 1e-9 * h, what);
    }
}

// In a plane of grid faces (x = 4h) every node on the plane has coplanar faces wider than a
// thin step's triangle: coplanar faces partly under the blade are clipped along its outline
// (paper Figure 7; cut_mesh decide_faces), the part under the blade opening, so the crack
// follows the blade step by step.
TEST(ScissorsSweeps, SmallStepsCutABeamThroughAlongGridFaces) {
  const double h = 0.01;
  const TetMesh beam = fixtures::box(8, 2, 2, 1, h);
  const double a0 = 80.0 * 3.141592653589793 / 180.0, a1 = -a0;
  for (int steps : {2, 4, 20}) {
    const SweepRun run =
        scissors(beam, Vec3(4.0 * h, -h, h), Vec3::UnitX(), 5.0 * h, a0, a1, steps);
    std::printf("scissors grid faces, %d steps: %d tets, pinned %lld\n", steps, run.mesh.num_tets(),
                static_cast<long long>(run.pinned));
    expect_cut_through(beam, run, Vec3::UnitX(), Vec3(4.0 * h, -h, h), 1e-9 * h,
                       std::to_string(steps) + " steps");
  }
}

// The tilted plane in 20 steps (it used to pin 20 tets and stay in one piece: tets a step's
// triangle only touched, crossed as a strip or along a coplanar edge were split welded and
// blocked the crack). Partial tets are now split by the plane itself, so nothing pins, and a
// welded segment lying along this step's trailing edge (the previous crack front) has no
// spurious crossing, so the crack carries on across every step line.
TEST(ScissorsSweeps, SmallStepsCutABeamThroughTilted20Steps) {
  const double h = 0.01;
  const TetMesh beam = fixtures::box(8, 2, 2, 1, h);
  const double a0 = 80.0 * 3.141592653589793 / 180.0, a1 = -a0;
  const Vec3 hinge(4.5 * h, -h, h), n = Vec3(1.0, 0.15, -0.1).normalized();
  const SweepRun run = scissors(beam, hinge, n, 5.0 * h, a0, a1, 20);
  expect_cut_through(beam, run, n, hinge, 1e-9 * h, "tilted, 20 steps");
}

}  // namespace
}  // namespace serosa::cutting

namespace serosa::cutting {
namespace {

// Mesh growth on repeated small cuts along a path in a plane of grid faces (a scissors closing
// in 47 steps over a 24-tet bar, each step's trailing edge on the previous crack front): every
// step only clips the coplanar faces its outline crosses. A clipped face has at most 3 nodes,
// 2 crossings per edge (6), 3 blade corners and a centroid pair, n <= 13 points, so at most
// 2n - 5 = 21 triangles, each coned from the off-plane node of each tet holding the face: a
// touched tet gives at most 21 tets (an edge split at most 3, a relabelled tet 1). Every step
// passes the invariant checker, pins nothing, and the bar ends in two pieces. The tets touched
// per step are reported, not bounded: they still grow by about 5 per step here (so the mesh
// grows quadratically in the steps), and off the grid planes much faster (docs/BENCHMARKS.md
// "Cutting", mesh growth).
TEST(ScissorsSweeps, RepeatedSmallCutsInAGridPlaneCreateAtMost21TetsPerTouchedTet) {
  const double h = 0.01;
  const TetMesh bar = fixtures::box(4, 1, 1, 1, h);
  const Vec3 hinge(2.0 * h, -h, 0.5 * h), n = Vec3::UnitX();
  const double a0 = 80.0 * 3.141592653589793 / 180.0, a1 = -a0;
  const int steps = 47;
  TetMesh m = bar;
  const Vec3 ea = n.unitOrthogonal(), eb = n.cross(ea);
  auto tip = [&](double t) -> Vec3 {
    return hinge + 3.0 * h * (std::cos(t) * ea + std::sin(t) * eb);
  };
  std::int64_t max_added = 0, max_touched = 0;
  double min_quality = 1.0;
  for (int k = 0; k < steps; ++k) {
    const double s0 = a0 + (a1 - a0) * k / steps, s1 = a0 + (a1 - a0) * (k + 1) / steps;
    auto blade = ConvexPolygon::make({hinge, tip(s0), tip(s1)});
    ASSERT_TRUE(blade.has_value());
    const testing::Applied a = testing::cut_and_check(m, *blade);
    ASSERT_TRUE(a.report.ok) << "step " << k << ": " << problems(a.report);
    const CutStats& st = a.result.stats;
    EXPECT_EQ(st.tets_pinned, 0) << k;
    EXPECT_LE(st.tets_added, 21 * st.tets_removed) << k;
    max_added = std::max(max_added, st.tets_added - st.tets_removed);
    max_touched = std::max(max_touched, st.tets_removed);
    if (st.tets_removed > 0) min_quality = std::min(min_quality, a.report.min_quality);
    m = a.after;
  }
  std::printf(
      "grid-plane path, 47 steps on a 24-tet bar: %d tets at the end, net tets per step "
      "max %lld, tets touched per step max %lld, min quality %g\n",
      m.num_tets(), static_cast<long long>(max_added), static_cast<long long>(max_touched),
      min_quality);
  EXPECT_EQ(count_components(m), 2);
}

}  // namespace
}  // namespace serosa::cutting

namespace serosa::cutting {
namespace {

struct GrowthRun {
  std::vector<std::int64_t> net;  ///< tets added - tets removed, per step with a blade
  std::int64_t max_touched = 0;   ///< most tets one step removed
  std::int64_t pinned = 0;
  std::int64_t new_crossing_edges = 0;  ///< straddling tets' crossing edges not in the original
  int tets = 0;
  double min_quality = 1.0;
  int pieces = 0;
  std::string failure;
};

// A scissors closing in `steps` thin steps over `start` in the plane (n, hinge) (blade `length`
// m, from 80 deg to -80 deg), each step checked by the invariant checker; after each step every
// tet that straddles the plane (nodes beyond the cut's tolerance on both sides) is checked to
// cross it only along edges of `start`.
GrowthRun growth(const TetMesh& start, const Vec3& hinge, const Vec3& n, double length, int steps) {
  GrowthRun g;
  std::unordered_set<std::uint64_t> original;
  for (const Tet& t : start.tets)
    for (int i = 0; i < 4; ++i)
      for (int j = i + 1; j < 4; ++j) original.insert(edge_key(t[i], t[j]));
  TetMesh m = start;
  const double a0 = 80.0 * 3.141592653589793 / 180.0, a1 = -a0;
  const Vec3 ea = n.unitOrthogonal(), eb = n.cross(ea);
  auto tip = [&](double t) -> Vec3 {
    return hinge + length * (std::cos(t) * ea + std::sin(t) * eb);
  };
  double tol = 0.0;  // the cuts' classification tolerance, m
  for (int k = 0; k < steps; ++k) {
    const double s0 = a0 + (a1 - a0) * k / steps, s1 = a0 + (a1 - a0) * (k + 1) / steps;
    auto blade = ConvexPolygon::make({hinge, tip(s0), tip(s1)});
    if (!blade) continue;
    const testing::Applied a = testing::cut_and_check(m, *blade);
    const CutStats& st = a.result.stats;
    if (!a.report.ok || st.degenerate_tets != 0) {
      g.failure = "step " + std::to_string(k) + ": " + problems(a.report);
      return g;
    }
    g.net.push_back(st.tets_added - st.tets_removed);
    g.max_touched = std::max(g.max_touched, st.tets_removed);
    g.pinned += st.tets_pinned;
    if (st.tets_removed > 0) g.min_quality = std::min(g.min_quality, a.report.min_quality);
    m = a.after;
    tol = std::max(tol, st.tolerance_m);  // (0 when the blade misses the mesh)
    for (const Tet& t : m.tets) {
      std::array<double, 4> phi{};
      for (int i = 0; i < 4; ++i) phi[static_cast<std::size_t>(i)] = n.dot(m.x[t[i]] - hinge);
      for (int i = 0; i < 4; ++i)
        for (int j = i + 1; j < 4; ++j) {
          const double pi = phi[static_cast<std::size_t>(i)], pj = phi[static_cast<std::size_t>(j)];
          if (((pi > tol && pj < -tol) || (pi < -tol && pj > tol)) &&
              original.count(edge_key(t[i], t[j])) == 0) {
            ++g.new_crossing_edges;
          }
        }
    }
  }
  g.tets = m.num_tets();
  g.pieces = count_components(m);
  return g;
}

// Mesh growth on repeated small cuts off the grid planes (issue 3: "the number of tets created
// per cut stays small"): a scissors closing in 47 thin steps over a 24-tet bar and a 384-tet
// beam, in an axis plane off the grid and in a tilted plane. Each step is valid, pins nothing,
// and the mesh ends in two pieces.
//
// Why the growth is bounded (it used to double per step: 906k tets after 29 steps): a partial
// tet is split by the plane itself (each side's piece coned from a Steiner point on its own
// side), and a tet split only because a neighbour put a point on one of its crossing edges is
// coned from its section's centroid, which lies on the plane. So no cut ever makes a new edge
// that crosses the plane: every tet straddling the plane crosses it along edges of the original
// mesh (checked below after every step), a crossing edge that gets a point stops crossing, and
// the straddling descendants of an original tet are finitely many however many steps cut near
// them. What remains per step is bounded by the pieces per touched tet (CutMesh.
// GrowthIsBoundedAndReported: 6 per complete tet, 94 per partial tet, 21 per tet holding a
// clipped coplanar face, 12 per neighbour) times the tets touched, and the tets touched grow at
// most linearly with the steps (each step line adds its crossings with the welded coplanar faces
// ahead of the crack front). Measured: at most 293 net tets per step on the bar, 591 on the beam
// (docs/BENCHMARKS.md, Cutting); the asserted constant, 1000 per step, leaves room for that, and
// the old doubling exceeded it by the 11th step that touched the bar.
TEST(ScissorsSweeps, RepeatedSmallCutsOffTheGridPlanesStayBoundedPerStep) {
  const double h = 0.01;
  const TetMesh bar = fixtures::box(4, 1, 1, 1, h);
  const TetMesh beam = fixtures::box(8, 2, 2, 1, h);
  struct Case {
    const TetMesh* mesh;
    Vec3 hinge, n;
    double length;
    const char* name;
  };
  const Vec3 tilt = Vec3(1.0, 0.15, -0.1).normalized();
  const std::vector<Case> cases{
      {&bar, Vec3(2.37 * h, -h, 0.5 * h), Vec3::UnitX(), 3.0 * h, "bar, x = 2.37 cm"},
      {&bar, Vec3(2.0 * h, -h, 0.5 * h), tilt, 3.0 * h, "bar, tilted"},
      {&beam, Vec3(4.37 * h, -h, h), Vec3::UnitX(), 5.0 * h, "beam, x = 4.37 cm"},
      {&beam, Vec3(4.5 * h, -h, h), tilt, 5.0 * h, "beam, tilted"},
  };
  constexpr std::int64_t kMaxNetPerStep = 1000;
  for (const Case& c : cases) {
    const GrowthRun g = growth(*c.mesh, c.hinge, c.n, c.length, 47);
    ASSERT_TRUE(g.failure.empty()) << c.name << ": " << g.failure;
    std::int64_t max_net = 0;
    std::string seq;
    for (std::int64_t v : g.net) {
      max_net = std::max(max_net, v);
      if (v != 0) seq.append(" ").append(std::to_string(v));
    }
    std::printf(
        "off-grid path, 47 steps, %s: %d tets at the end, net tets per step max %lld, tets "
        "touched per step max %lld, min quality %g; net per step:%s\n",
        c.name, g.tets, static_cast<long long>(max_net), static_cast<long long>(g.max_touched),
        g.min_quality, seq.c_str());
    EXPECT_EQ(g.pinned, 0) << c.name;
    EXPECT_EQ(g.new_crossing_edges, 0) << c.name;
    EXPECT_LE(max_net, kMaxNetPerStep) << c.name;
    EXPECT_EQ(g.pieces, 2) << c.name;
  }
}

}  // namespace
}  // namespace serosa::cutting
