// A scissors closing over a beam in many small steps (partial cuts). Three ways to cut it:
//  - step by step: each step's polygon is the thin triangle from the hinge it swept in that step,
//    sharing its trailing edge with the previous step's leading edge, cut with cut_mesh into the
//    mesh the previous steps made, along their crack front;
//  - swept so far: each step's polygon is the whole sector the blade has swept since the stroke
//    began (hinge plus the arc of the tip), cut with cut_mesh into the mesh the previous steps
//    made;
//  - progressive: each step's thin triangle goes to one ProgressiveCut (cutting/progressive_cut.h),
//    which re-cuts the tets the stroke touched, as they were before it, by the sector swept so
//    far; every step is checked against the beam before the stroke and that sector.
// The crack stops where the blade ends, but tets the blade has crossed open: at the end the beam
// is in two pieces, one on each side, with volume conserved, and every intermediate mesh passes
// the invariant checker.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <random>
#include <stdexcept>

#include "cut_helpers.h"
#include "cutting/progressive_cut.h"
#include "mesh_fixtures.h"

namespace serosa::cutting {
namespace {

using testing::problems;

enum class Polygon { kStep, kSweptSoFar, kProgressive };

struct SweepRun {
  TetMesh mesh;
  int steps_done = 0;
  std::int64_t pinned = 0;
  std::string failure;
};

// A scissors blade hinged at `hinge`, rotating in the plane through it with unit normal n (in-
// plane axes e1, e2) from angle a0 to a1 (rad) in `steps` steps; each step's polygon (the
// triangle (hinge, tip before, tip after), or the hinge and the tip's positions from the first
// to this step) is cut and checked in turn.
SweepRun scissors(const TetMesh& beam, const Vec3& hinge, const Vec3& n, double length, double a0,
                  double a1, int steps, Polygon kind = Polygon::kStep) {
  SweepRun run{beam, 0, 0, {}};
  ProgressiveCut stroke;
  const Vec3 a = n.unitOrthogonal(), b = n.cross(a);
  auto tip = [&](double t) -> Vec3 { return hinge + length * (std::cos(t) * a + std::sin(t) * b); };
  for (int k = 0; k < steps; ++k) {
    const double s0 = a0 + (a1 - a0) * k / steps, s1 = a0 + (a1 - a0) * (k + 1) / steps;
    std::vector<Vec3> corners{hinge, tip(s0), tip(s1)};
    if (kind == Polygon::kSweptSoFar) {
      corners.resize(1);
      for (int j = 0; j <= k + 1; ++j) corners.push_back(tip(a0 + (a1 - a0) * j / steps));
    }
    auto blade = ConvexPolygon::make(corners);
    if (!blade) continue;
    const bool progressive = kind == Polygon::kProgressive;
    const CutResult r = progressive ? stroke.cut(run.mesh, *blade) : cut_mesh(run.mesh, *blade);
    TetMesh after = run.mesh;
    TopologyDelta d = r.delta;
    try {
      apply(after, d);
    } catch (const std::invalid_argument& e) {
      run.failure = "step " + std::to_string(k) + ": apply() rejected: " + e.what();
      return run;
    }
    if (progressive) {
      stroke.applied(after, d);
      if (!stroke.last_step().extended && k > 0) {
        run.failure = "step " + std::to_string(k) + " did not extend the stroke";
        return run;
      }
    }
    CutCheckOptions co;
    co.geometry_tol_m = 4.0 * r.stats.tolerance_m + 1e-12;
    co.plane_tol_m = r.stats.tolerance_m;
    // A progressive step is checked as what it is: the mesh before the stroke cut by the region
    // swept so far (its nodes released from the previous step's pieces are in no tet).
    co.unused_nodes_ok = progressive;
    const CutCheckReport rep = progressive ? check_cut(beam, after, *stroke.region(), co)
                                           : check_cut(run.mesh, after, *blade, co);
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
  const TetMesh beam = test_meshes::kuhn_box(8, 2, 2, 1, h);
  TetMesh jittered = test_meshes::kuhn_box(8, 2, 2, 1, h);
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
    for (int steps : {2, 4, 20})
      for (Polygon kind : {Polygon::kStep, Polygon::kSweptSoFar, Polygon::kProgressive}) {
        const bool step = kind == Polygon::kStep;
        if (step && c.mesh == &beam && c.n != Vec3::UnitX() && steps == 20) continue;  // below
        const SweepRun run = scissors(*c.mesh, c.hinge, c.n, 5.0 * h, a0, a1, steps, kind);
        const std::string what = std::string(c.name) + ", " + std::to_string(steps) + " steps" +
                                 (step                           ? ", step by step"
                                  : kind == Polygon::kSweptSoFar ? ", swept so far"
                                                                 : ", progressive");
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
  const TetMesh beam = test_meshes::kuhn_box(8, 2, 2, 1, h);
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

// Cutting thin steps one by one with cut_mesh, off the grid planes. The tilted plane in 20 thin
// steps meets tets whose section a step's triangle only grazes (S has no area: split welded),
// crosses as a strip (two fronts no single apex touches: the crack there is fanned short of the
// blade), or whose section side along a coplanar edge (the previous steps' nodes on the plane)
// its outline crosses. Those used to be pinned (split with every node welded), and the beam cut
// step by step stayed in one piece; since the crossings of coplanar edges are welded nodes the
// crack stops on, nothing is pinned and it falls in two, exactly along the plane (asserted).
// Cut as one progressive stroke, every step is one cut of the sector swept so far, and the beam
// falls in two with far fewer tets (asserted).
TEST(ScissorsSweeps, SmallStepsTiltedIn20ThinStepsSeparateStepByStepAndAsAStroke) {
  const double h = 0.01;
  const TetMesh beam = test_meshes::kuhn_box(8, 2, 2, 1, h);
  const double a0 = 80.0 * 3.141592653589793 / 180.0, a1 = -a0;
  const Vec3 hinge(4.5 * h, -h, h), n = Vec3(1.0, 0.15, -0.1).normalized();
  const SweepRun run = scissors(beam, hinge, n, 5.0 * h, a0, a1, 20, Polygon::kStep);
  ASSERT_TRUE(run.failure.empty()) << run.failure;
  EXPECT_EQ(run.steps_done, 20);
  std::printf("scissors tilted, 20 thin steps: %d tets, pinned %lld, pieces %d\n",
              run.mesh.num_tets(), static_cast<long long>(run.pinned), count_components(run.mesh));
  EXPECT_EQ(run.pinned, 0);
  expect_cut_through(beam, run, n, hinge, 1e-9 * h, "tilted, 20 thin steps, step by step");
  const SweepRun pro = scissors(beam, hinge, n, 5.0 * h, a0, a1, 20, Polygon::kProgressive);
  std::printf("scissors tilted, 20 thin steps, progressive: %d tets, pinned %lld, pieces %d\n",
              pro.mesh.num_tets(), static_cast<long long>(pro.pinned), count_components(pro.mesh));
  expect_cut_through(beam, pro, n, hinge, 1e-9 * h, "tilted, 20 steps, progressive");
  EXPECT_LT(pro.mesh.num_tets(), run.mesh.num_tets());
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
  const TetMesh bar = test_meshes::kuhn_box(4, 1, 1, 1, h);
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
