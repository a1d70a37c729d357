// ProgressiveCut (cutting/progressive_cut.h): a stroke cut while it progresses. The invariant:
// after every step the mesh is the mesh before the stroke cut once, by cut_mesh, by the region
// swept so far (the incremental result equals the full rebuild, up to node numbering and the
// quad diagonals that follow it: same_cut below), and passes the invariant checker
// against the mesh before the stroke; so the tets a stroke creates do not depend on how finely it
// was stepped. Also convex_union, and the cases that end a stroke.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <functional>
#include <random>
#include <string>

#include "cut_helpers.h"
#include "cutting/progressive_cut.h"
#include "engine/boundary.h"
#include "engine/mesh_check.h"
#include "mesh_fixtures.h"

namespace serosa::cutting {
namespace {

using testing::problems;

constexpr double kPi = 3.141592653589793;

// ---- convex_union ---------------------------------------------------------------------------

TEST(ConvexUnion, MergesCoplanarNeighboursWhoseUnionIsConvex) {
  const Vec3 o(0.0, 0.0, 0.0), a(1.0, 0.0, 0.0), b(0.0, 1.0, 0.0), c(-1.0, 0.0, 0.0);
  const ConvexPolygon t1({o, a, b}), t2({o, b, c});  // a fan from o: a half disc's triangles
  const auto u = convex_union(t1, t2);
  ASSERT_TRUE(u);
  EXPECT_NEAR(u->area(), 1.0, 1e-15);
  EXPECT_EQ(u->size(), 3u);  // o lies on the edge a-c: dropped as collinear
  EXPECT_NEAR(u->normal().dot(t1.normal()), 1.0, 1e-15);
  // b given clockwise (opposite normal): the union keeps a's orientation.
  const ConvexPolygon t2r({o, c, b});
  const auto ur = convex_union(t1, t2r);
  ASSERT_TRUE(ur);
  EXPECT_NEAR(ur->normal().dot(t1.normal()), 1.0, 1e-15);
  // Inside: the union is the region itself.
  const ConvexPolygon small({Vec3(0.1, 0.1, 0.0), Vec3(0.2, 0.1, 0.0), Vec3(0.1, 0.2, 0.0)});
  const auto us = convex_union(t1, small);
  ASSERT_TRUE(us);
  EXPECT_NEAR(us->area(), t1.area(), 1e-15);
}

TEST(ConvexUnion, RefusesGapsNonConvexUnionsAndOtherPlanes) {
  const ConvexPolygon sq({Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(1, 1, 0), Vec3(0, 1, 0)});
  // Apart: the hull would cover the gap.
  const ConvexPolygon far({Vec3(2, 0, 0), Vec3(3, 0, 0), Vec3(3, 1, 0), Vec3(2, 1, 0)});
  EXPECT_FALSE(convex_union(sq, far));
  // An L: sharing half an edge.
  const ConvexPolygon l({Vec3(1, 0, 0), Vec3(2, 0, 0), Vec3(2, 0.5, 0), Vec3(1, 0.5, 0)});
  EXPECT_FALSE(convex_union(sq, l));
  // Side by side along a whole edge: a rectangle.
  const ConvexPolygon r({Vec3(1, 0, 0), Vec3(2, 0, 0), Vec3(2, 1, 0), Vec3(1, 1, 0)});
  const auto u = convex_union(sq, r);
  ASSERT_TRUE(u);
  EXPECT_NEAR(u->area(), 2.0, 1e-14);
  // Overlapping by half: a 1.5 x 1 rectangle.
  const ConvexPolygon ov({Vec3(0.5, 0, 0), Vec3(1.5, 0, 0), Vec3(1.5, 1, 0), Vec3(0.5, 1, 0)});
  const auto uo = convex_union(sq, ov);
  ASSERT_TRUE(uo);
  EXPECT_NEAR(uo->area(), 1.5, 1e-14);
  // Tilted out of the plane by 1e-6 rad, or lifted by 1e-6: refused.
  const ConvexPolygon tilt({Vec3(1, 0, 0), Vec3(2, 0, 1e-6), Vec3(2, 1, 1e-6), Vec3(1, 1, 0)});
  EXPECT_FALSE(convex_union(sq, tilt));
  const ConvexPolygon lift(
      {Vec3(1, 0, 1e-6), Vec3(2, 0, 1e-6), Vec3(2, 1, 1e-6), Vec3(1, 1, 1e-6)});
  EXPECT_FALSE(convex_union(sq, lift));
}

// ---- stroke = one cut of the region swept so far --------------------------------------------

// True when every point of a matches a distinct point of b within tol (m), and the counts agree.
bool same_points(std::vector<Vec3> a, std::vector<Vec3> b, double tol) {
  if (a.size() != b.size()) return false;
  auto by_x = [](const Vec3& u, const Vec3& v) { return u.x() < v.x(); };
  std::sort(a.begin(), a.end(), by_x);
  std::sort(b.begin(), b.end(), by_x);
  std::vector<char> used(b.size(), 0);
  for (const Vec3& p : a) {
    auto it = std::lower_bound(b.begin(), b.end(), Vec3(p.x() - tol, 0.0, 0.0), by_x);
    bool found = false;
    for (; it != b.end() && it->x() <= p.x() + tol && !found; ++it) {
      const auto j = static_cast<std::size_t>(it - b.begin());
      if (!used[j] && (*it - p).norm() <= tol) used[j] = 1, found = true;
    }
    if (!found) return false;
  }
  return true;
}

// True when a and b are the same cut mesh up to node numbering and the triangulation of the
// pieces' quads and face fans (those follow node ids, and new nodes are numbered in the order the
// cut visits tets, which differs between a stroke's local mesh and the whole mesh): as many tets,
// the same nodes in use (rest positions, opened pairs twice), the same pieces with the same rest
// volumes, and the same boundary area (rest).
bool same_cut(const TetMesh& a, const TetMesh& b, double tol, std::string& why) {
  if (a.num_tets() != b.num_tets()) {
    why = std::to_string(a.num_tets()) + " tets against " + std::to_string(b.num_tets());
    return false;
  }
  auto used_nodes = [](const TetMesh& m) {
    std::vector<char> used(static_cast<std::size_t>(m.num_nodes()), 0);
    for (const Tet& t : m.tets)
      for (std::int32_t v : t) used[static_cast<std::size_t>(v)] = 1;
    std::vector<Vec3> p;
    for (std::size_t i = 0; i < used.size(); ++i)
      if (used[i]) p.push_back(m.rest[i]);
    return p;
  };
  if (!same_points(used_nodes(a), used_nodes(b), tol)) {
    why = "the nodes in use differ";
    return false;
  }
  auto piece_volumes = [](const TetMesh& m) {
    const std::vector<std::int32_t> comp = tet_components(m);
    std::vector<double> v;
    for (std::int32_t t = 0; t < m.num_tets(); ++t) {
      const auto c = static_cast<std::size_t>(comp[static_cast<std::size_t>(t)]);
      if (v.size() <= c) v.resize(c + 1, 0.0);
      v[c] += m.rest_volume(t);
    }
    std::sort(v.begin(), v.end());
    return v;
  };
  const std::vector<double> va = piece_volumes(a), vb = piece_volumes(b);
  bool same = va.size() == vb.size();
  for (std::size_t k = 0; k < va.size() && same; ++k)
    same = std::abs(va[k] - vb[k]) <= 1e-12 * (va.back() + vb.back());
  if (!same) {
    why = "pieces differ: " + std::to_string(va.size()) + " against " + std::to_string(vb.size());
    return false;
  }
  auto boundary_area = [](const TetMesh& m) {
    double area = 0.0;
    for (const BoundaryFace& f : face_census(m).boundary) {
      const Vec3& p = m.rest[static_cast<std::size_t>(f.nodes[0])];
      area += 0.5 * (m.rest[static_cast<std::size_t>(f.nodes[1])] - p)
                        .cross(m.rest[static_cast<std::size_t>(f.nodes[2])] - p)
                        .norm();
    }
    return area;
  };
  const double aa = boundary_area(a), ab = boundary_area(b);
  if (std::abs(aa - ab) > 1e-9 * ab) {
    why = "boundary areas differ: " + std::to_string(aa) + " against " + std::to_string(ab);
    return false;
  }
  return true;
}

struct StrokeReport {
  std::string failure;
  int steps = 0;
  int extended = 0;
  TetMesh mesh;
  std::int64_t released = 0;
};

// Cuts `m0` by `polygons` in turn through one ProgressiveCut; after every step: apply() accepts
// the delta, the mesh passes check_cut against m0 and the region, equals cut_mesh(m0, region)
// geometrically, and the nodes in no tet are exactly the nodes released so far.
// With `move`, the tissue moves between steps (as the FEM moves it): move(k, x) displaces every
// current position before step k, and the reference is m0 with its nodes where they are now.
using Motion = std::function<void(int, TetMesh&)>;
StrokeReport run_stroke(const TetMesh& m0_rest, const std::vector<ConvexPolygon>& polygons,
                        const Motion& move = {}) {
  StrokeReport rep;
  rep.mesh = m0_rest;
  ProgressiveCut stroke;
  TetMesh m0 = m0_rest;
  for (std::size_t k = 0; k < polygons.size(); ++k) {
    const std::string at = "step " + std::to_string(k) + ": ";
    if (move) {
      move(static_cast<int>(k), rep.mesh);
      for (std::size_t i = 0; i < m0.x.size(); ++i) m0.x[i] = rep.mesh.x[i];
    }
    const CutResult r = stroke.cut(rep.mesh, polygons[k]);
    TetMesh after = rep.mesh;
    TopologyDelta d = r.delta;
    try {
      apply(after, d);
    } catch (const std::invalid_argument& e) {
      rep.failure = at + "apply() rejected: " + e.what();
      return rep;
    }
    stroke.applied(after, d);
    if (k > 0 && !stroke.last_step().extended) {
      rep.failure = at + "the polygon did not extend the stroke";
      return rep;
    }
    rep.extended += stroke.last_step().extended ? 1 : 0;
    rep.released += stroke.last_step().nodes_released;
    const ConvexPolygon& region = *stroke.region();
    CutCheckOptions co;
    co.geometry_tol_m = 4.0 * r.stats.tolerance_m + 1e-12;
    co.plane_tol_m = r.stats.tolerance_m;
    co.unused_nodes_ok = true;
    const CutCheckReport check = check_cut(m0, after, region, co);
    if (!check.ok || r.stats.degenerate_tets != 0) {
      rep.failure = at + problems(check);
      return rep;
    }
    TetMesh once = m0;
    TopologyDelta od = cut_mesh(m0, region).delta;
    apply(once, od);
    std::string why;
    if (!same_cut(after, once, 1e-9 * region.diameter(), why)) {
      rep.failure = at + "differs from one cut of the region swept so far: " + why;
      return rep;
    }
    std::vector<char> used(static_cast<std::size_t>(after.num_nodes()), 0);
    for (const Tet& t : after.tets)
      for (std::int32_t v : t) used[static_cast<std::size_t>(v)] = 1;
    const auto unused = std::count(used.begin(), used.end(), 0);
    if (unused != rep.released) {
      rep.failure = at + std::to_string(unused) + " nodes in no tet, " +
                    std::to_string(rep.released) + " released";
      return rep;
    }
    rep.mesh = std::move(after);
    ++rep.steps;
  }
  return rep;
}

// The thin triangles of a scissors blade (hinge, length) closing from a0 to a1 (rad) in `steps`
// steps in the plane with unit normal n.
std::vector<ConvexPolygon> fan(const Vec3& hinge, const Vec3& n, double length, double a0,
                               double a1, int steps) {
  const Vec3 a = n.unitOrthogonal(), b = n.cross(a);
  auto tip = [&](double t) -> Vec3 { return hinge + length * (std::cos(t) * a + std::sin(t) * b); };
  std::vector<ConvexPolygon> out;
  for (int k = 0; k < steps; ++k) {
    auto p = ConvexPolygon::make(
        {hinge, tip(a0 + (a1 - a0) * k / steps), tip(a0 + (a1 - a0) * (k + 1) / steps)});
    if (p) out.push_back(*p);
  }
  return out;
}

// The scissors cases of the growth table (docs/BENCHMARKS.md "Cutting"): cut step by step with
// cut_mesh the tilted bar grew to 906k tets after 29 of 47 steps; as a stroke every step equals
// one cut of the sector swept so far, so the count stays that of a single cut.
TEST(ProgressiveCut, EveryStepEqualsOneCutOfTheRegionSweptSoFar) {
  const double h = 0.01;
  const TetMesh bar = test_meshes::kuhn_box(4, 1, 1, 1, h);
  const TetMesh beam = test_meshes::kuhn_box(8, 2, 2, 1, h);
  struct Case {
    const TetMesh* mesh;
    Vec3 hinge, n;
    double length;
    int steps;
    const char* name;
  };
  const double a0 = 80.0 * kPi / 180.0;
  const std::vector<Case> cases{
      {&bar, Vec3(2.37 * h, -0.5 * h, 0.5 * h), Vec3::UnitX(), 3.0 * h, 47, "bar, x = 2.37 cm"},
      {&bar, Vec3(2.0 * h, -0.5 * h, 0.5 * h), Vec3::UnitX(), 3.0 * h, 47, "bar, grid plane"},
      {&bar, Vec3(2.2 * h, -0.5 * h, 0.5 * h), Vec3(1.0, 0.15, -0.1).normalized(), 3.0 * h, 47,
       "bar, tilted"},
      {&beam, Vec3(4.5 * h, -h, h), Vec3(1.0, 0.15, -0.1).normalized(), 5.0 * h, 20,
       "beam, tilted"},
  };
  for (const Case& c : cases) {
    const StrokeReport rep = run_stroke(*c.mesh, fan(c.hinge, c.n, c.length, a0, -a0, c.steps));
    ASSERT_TRUE(rep.failure.empty()) << c.name << ": " << rep.failure;
    EXPECT_EQ(rep.extended, c.steps - 1) << c.name;
    EXPECT_EQ(count_components(rep.mesh), 2) << c.name;
    std::printf("stroke %s, %d steps: %d tets, %lld nodes released\n", c.name, c.steps,
                rep.mesh.num_tets(), static_cast<long long>(rep.released));
  }
}

// The same while the tissue moves between steps (a smooth displacement of up to 0.05 of a cell
// that changes every step, as the FEM would move it): every step still equals one cut, of the
// mesh before the stroke with its nodes where they are now, by the region swept so far; the
// stroke's pieces are re-made from the originals' nodes, never re-cut.
TEST(ProgressiveCut, EveryStepEqualsOneCutWhileTheTissueMoves) {
  const double h = 0.01;
  const TetMesh beam = test_meshes::kuhn_box(8, 2, 2, 1, h);
  const Motion move = [h](int k, TetMesh& m) {
    for (std::size_t i = 0; i < m.x.size(); ++i) {
      const Vec3& r = m.rest[i];
      m.x[i] = r + 0.05 * h *
                       Vec3(std::sin(40.0 * r.y() + 0.3 * k), std::sin(30.0 * r.z() + 0.2 * k),
                            std::sin(20.0 * r.x() - 0.1 * k));
    }
  };
  const double a0 = 80.0 * kPi / 180.0;
  const Vec3 n = Vec3(1.0, 0.15, -0.1).normalized();
  const StrokeReport rep =
      run_stroke(beam, fan(Vec3(4.5 * h, -h, h), n, 5.0 * h, a0, -a0, 20), move);
  ASSERT_TRUE(rep.failure.empty()) << rep.failure;
  EXPECT_EQ(rep.extended, 19);
  EXPECT_EQ(count_components(rep.mesh), 2);
}

// Random strokes: fans from random hinges in random planes (some exactly through grid nodes and
// faces, some in a jittered mesh), and blade edges pushed along a line (parallelogram unions),
// 2-12 steps each.
TEST(ProgressiveCut, RandomStrokesEqualOneCutAtEveryStep) {
  std::mt19937 rng(20261124);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  const double h = 0.01;
  const TetMesh grid = test_meshes::kuhn_box(4, 3, 3, 2, h);
  TetMesh jittered = test_meshes::kuhn_box(4, 3, 3, 2, h);
  for (std::size_t i = 0; i < jittered.rest.size(); ++i) {
    for (int c = 0; c < 3; ++c) jittered.rest[i][c] += 0.15 * h * (u(rng) - 0.5);
    jittered.x[i] = jittered.rest[i];
  }
  int strokes = 0, separated = 0;
  for (int s = 0; s < 120; ++s) {
    const bool jit = s % 3 == 2;
    const TetMesh& m0 = jit ? jittered : grid;
    const int steps = 2 + static_cast<int>(u(rng) * 11.0);
    Vec3 n;
    if (s % 3 == 0) {  // an axis plane, half the time through grid nodes
      n = Vec3::Unit(static_cast<Eigen::Index>(u(rng) * 3.0) % 3);
    } else {
      n = Vec3(u(rng) - 0.5, u(rng) - 0.5, u(rng) - 0.5).normalized();
    }
    const Vec3 centre(h * (1.0 + 2.0 * u(rng)), h * (0.5 + 2.0 * u(rng)), h * (0.5 + 2.0 * u(rng)));
    Vec3 p = centre;
    if (s % 3 == 0 && s % 2 == 0) {
      const Eigen::Index axis = n.x() != 0.0 ? 0 : (n.y() != 0.0 ? 1 : 2);
      p[axis] = h * std::round(p[axis] / h);
    }
    std::vector<ConvexPolygon> polys;
    if (s % 4 != 3) {
      const Vec3 a = n.unitOrthogonal();
      const double a0 = 2.0 * kPi * u(rng), span = (0.4 + 2.2 * u(rng));
      polys = fan(p - 2.0 * h * a, n, 3.0 * h + 6.0 * h * u(rng), a0, a0 + span, steps);
    } else {  // a blade edge pushed along a line in the plane
      const Vec3 a = n.unitOrthogonal(), b = n.cross(a);
      const Vec3 e0 = p - 4.0 * h * a, e1 = p + 4.0 * h * a;
      const double len = 6.0 * h * u(rng) + h;
      for (int k = 0; k < steps; ++k) {
        const Vec3 d0 = b * (len * k / steps - 0.5 * len),
                   d1 = b * (len * (k + 1) / steps - 0.5 * len);
        auto q = ConvexPolygon::make({e0 + d0, e1 + d0, e1 + d1, e0 + d1});
        if (q) polys.push_back(*q);
      }
    }
    if (polys.empty()) continue;
    const StrokeReport rep = run_stroke(m0, polys);
    ASSERT_TRUE(rep.failure.empty()) << "stroke " << s << ": " << rep.failure;
    ++strokes;
    separated += count_components(rep.mesh) > count_components(m0) ? 1 : 0;
  }
  std::printf("random strokes: %d, %d of them cut a piece off\n", strokes, separated);
  EXPECT_EQ(strokes, 120);
  EXPECT_GE(separated, 5);  // the checks above also ran on strokes that cut through
}

// What ends a stroke: a polygon in another plane, a polygon whose union with the region is not
// convex, or a topology change the stroke did not make. A polygon inside the region does nothing.
TEST(ProgressiveCut, OtherPlanesForeignChangesAndGapsBeginANewStroke) {
  const double h = 0.01;
  const TetMesh beam = test_meshes::kuhn_box(8, 2, 2, 1, h);
  const Vec3 n = Vec3(1.0, 0.15, -0.1).normalized(), hinge(4.5 * h, -h, h);
  const std::vector<ConvexPolygon> steps = fan(hinge, n, 5.0 * h, 1.2, 0.2, 6);
  TetMesh m = beam;
  ProgressiveCut stroke;
  auto step = [&](const ConvexPolygon& p) {
    const CutResult r = stroke.cut(m, p);
    TopologyDelta d = r.delta;
    apply(m, d);
    stroke.applied(m, d);
    return r;
  };
  for (std::size_t k = 0; k < 3; ++k) step(steps[k]);
  EXPECT_TRUE(stroke.active());
  const double area3 = stroke.region()->area();
  // Inside the region: empty delta, the stroke goes on.
  const CutResult inside = step(steps[1]);
  EXPECT_TRUE(inside.delta.empty());
  EXPECT_TRUE(stroke.last_step().inside);
  EXPECT_NEAR(stroke.region()->area(), area3, 1e-15);
  // A gap (step 5 without step 4): a new stroke from the mesh as it is, which then cuts exactly
  // what cut_mesh cuts.
  const TetMesh before5 = m;
  const CutResult r5 = step(steps[4]);
  EXPECT_FALSE(stroke.last_step().extended);
  EXPECT_EQ(stroke.last_step().pieces_replaced, 0);
  EXPECT_NEAR(stroke.region()->area(), steps[4].area(), 1e-15);
  EXPECT_EQ(r5.delta.removed_tets, cut_mesh(before5, steps[4]).delta.removed_tets);
  // Another plane (tilted by 0.01 rad about the hinge): a new stroke.
  const Vec3 n2 = Eigen::AngleAxisd(0.01, Vec3::UnitZ()) * n;
  step(fan(hinge, n2, 5.0 * h, 0.2, 0.0, 1).front());
  EXPECT_FALSE(stroke.last_step().extended);
  // A foreign change in between (another cut applied by someone else): a new stroke.
  step(fan(hinge, n2, 5.0 * h, 0.0, -0.2, 1).front());
  EXPECT_TRUE(stroke.last_step().extended);
  TopologyDelta other = cut_mesh(m, testing::square(Vec3::UnitX(), Vec3(1.5 * h, h, h), h)).delta;
  apply(m, other);
  step(fan(hinge, n2, 5.0 * h, -0.2, -0.4, 1).front());
  EXPECT_FALSE(stroke.last_step().extended);
  // end(): the same.
  stroke.end();
  EXPECT_FALSE(stroke.active());
  step(fan(hinge, n2, 5.0 * h, -0.4, -0.6, 1).front());
  EXPECT_FALSE(stroke.last_step().extended);
  // applied() with another delta than the one cut() returned: the stroke ends.
  ASSERT_TRUE(stroke.active());
  (void)stroke.cut(m, fan(hinge, n2, 5.0 * h, -0.6, -0.8, 1).front());
  TopologyDelta foreign = cut_mesh(m, testing::square(Vec3::UnitX(), Vec3(6.5 * h, h, h), h)).delta;
  ASSERT_FALSE(foreign.empty());
  apply(m, foreign);
  stroke.applied(m, foreign);
  EXPECT_FALSE(stroke.active());
  EXPECT_TRUE(check_mesh(m).problems.empty());
}

}  // namespace
}  // namespace serosa::cutting
