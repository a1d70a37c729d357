// The two baseline cutting methods and the method dispatch: element removal
// (cutting/remove_cut.h) and node snapping (cutting/snap_cut.h), each through the invariant
// checker (cutting/validate.h) where its invariants apply to the method:
//   remove: structure (finite, positive volumes, no face shared by more than two tets, consistent
//           orientation) applies; volume conservation does not (the removed tets are lost, and the
//           loss must equal their volume exactly); "no new unreferenced node" does not (the nodes
//           only removed tets used stay, unreferenced); "boundary faces on the blade" does not (the
//           new boundary is the neighbours' faces).
//   snap:   structure applies. On the box meshes below total volume is conserved (moved boundary
//           nodes slide within flat faces or along ridges; the blades stay away from corners) and
//           every new boundary face lies on the blade or on the old surface, but not always on
//           ONE old face as check_cut asks (a face whose node slid across an old face's edge
//           spans two old faces of the same flat side), so that is checked here point by point.
//           Per-group volume does not apply (nodes move across group interfaces), nor "no new
//           unreferenced node" (a moved node is replaced by a new one; the old one stays,
//           unreferenced), nor the pattern method's exact clipped volume (the crack follows mesh
//           faces). Pure snapping can fail to separate: an edge whose two ends each close a tet
//           whose three other nodes are already on the plane cannot be resolved (moving either
//           end flattens that tet); SnapStats::edges_unresolved counts them and the crack stays
//           welded there. Near-axis-aligned covering cuts of a grid always separate; steeper ones
//           do in most cases (counted below).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <random>
#include <set>
#include <string>
#include <vector>

#include "cut_helpers.h"
#include "cutting/cut_method.h"
#include "cutting/remove_cut.h"
#include "cutting/snap_cut.h"
#include "cutting/tet_bvh.h"
#include "cutting/validate.h"
#include "engine/boundary.h"
#include "engine/geometry/point_triangle.h"
#include "engine/mesh_check.h"
#include "engine/mesh_quality.h"
#include "engine/tet_faces.h"
#include "engine/topology_delta.h"
#include "mesh_fixtures.h"

namespace serosa::cutting {
namespace {

using testing::problems;
using testing::square;

constexpr bool kSanitized =
#if defined(__SANITIZE_ADDRESS__)
    true;
#else
    false;
#endif
constexpr int kCuts = kSanitized ? 30 : 100;

double total_volume(const TetMesh& m) {
  double v = 0.0;
  for (std::int32_t i = 0; i < m.num_tets(); ++i) v += m.rest_volume(i);
  return v;
}

// Independent oracle for "the tet meets the polygon": the polygon clipped by the tet's four
// half-spaces, each moved outward by grow (m; negative shrinks), is non-empty.
bool clip_oracle(const TetMesh& m, const Tet& t, const ConvexPolygon& blade, double grow) {
  std::vector<Vec3> poly = blade.points();
  for (int k = 0; k < 4; ++k) {
    const auto& f = kTetFaces[static_cast<std::size_t>(k)];  // the face opposite local node k
    const Vec3 &a = m.x[t[f[0]]], &b = m.x[t[f[1]]], &c = m.x[t[f[2]]], &o = m.x[t[k]];
    Vec3 n = (b - a).cross(c - a).normalized();
    if (n.dot(o - a) > 0.0) n = -n;  // outward
    const double off = n.dot(a) + grow;
    std::vector<Vec3> out;
    for (std::size_t i = 0; i < poly.size(); ++i) {
      const Vec3& p = poly[i];
      const Vec3& q = poly[(i + 1) % poly.size()];
      const double sp = n.dot(p) - off, sq = n.dot(q) - off;
      if (sp <= 0.0) out.push_back(p);
      if ((sp < 0.0 && sq > 0.0) || (sp > 0.0 && sq < 0.0))
        out.push_back(p + sp / (sp - sq) * (q - p));
    }
    poly = std::move(out);
    if (poly.empty()) return false;
  }
  return true;
}

// A random blade square through the box [0, L]^3's middle region, tilted at random.
ConvexPolygon random_blade(std::mt19937& rng, double L, double half) {
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  const Vec3 n(u(rng), u(rng), u(rng));
  const Vec3 c = Vec3::Constant(0.5 * L) + 0.15 * L * Vec3(u(rng), u(rng), u(rng));
  return square(n.norm() > 0.1 ? n : Vec3::UnitX(), c, half, u(rng) * 3.0);
}

// ---- remove -------------------------------------------------------------------------------

TEST(RemoveCut, TouchTestAgreesWithPolygonClipping) {
  std::mt19937 rng(7);
  std::int64_t touching = 0, apart = 0;
  for (int i = 0; i < 3000; ++i) {
    TetMesh m = fixtures::random_tet(rng);
    std::uniform_real_distribution<double> u(-1.0, 1.0);
    const ConvexPolygon blade = square(Vec3(u(rng), u(rng), u(rng)), Vec3(u(rng), u(rng), u(rng)),
                                       0.2 + 0.6 * (u(rng) + 1));
    const bool got = tet_touches_polygon(m.x[0], m.x[1], m.x[2], m.x[3], blade, 0.0);
    if (clip_oracle(m, m.tets[0], blade, -1e-9)) {
      EXPECT_TRUE(got) << "case " << i;
      ++touching;
    } else if (!clip_oracle(m, m.tets[0], blade, 1e-9)) {
      EXPECT_FALSE(got) << "case " << i;
      ++apart;
    }
  }
  EXPECT_GT(touching, 300);  // both outcomes well represented
  EXPECT_GT(apart, 300);
}

TEST(RemoveCut, TouchingCountsNodesEdgesAndFacesOnThePolygon) {
  // Unit tet with its face z = 0 on the blade plane, and one with only a node on it.
  const Vec3 a(0, 0, 0), b(1, 0, 0), c(0, 1, 0), d(0, 0, 1);
  const ConvexPolygon blade = square(Vec3::UnitZ(), Vec3(0.2, 0.2, 0.0), 0.1);
  EXPECT_TRUE(tet_touches_polygon(a, b, c, d, blade));
  const ConvexPolygon at_node = square(Vec3::UnitZ(), Vec3(0.0, 0.0, 1.0), 0.1);
  EXPECT_TRUE(tet_touches_polygon(a, b, c, d, at_node));
  const ConvexPolygon above = square(Vec3::UnitZ(), Vec3(0.0, 0.0, 1.0 + 1e-6), 0.1);
  EXPECT_FALSE(tet_touches_polygon(a, b, c, d, above));
  // Plane crosses the tet but the polygon lies beside it, though within its bounding box.
  const ConvexPolygon beside = square(Vec3::UnitZ(), Vec3(0.7, 0.7, 0.1), 0.1);
  EXPECT_FALSE(tet_touches_polygon(a, b, c, d, beside));
}

TEST(RemoveCut, RemovesExactlyTheTouchedTetsAndLosesTheirVolume) {
  std::mt19937 rng(11);
  for (int i = 0; i < kCuts; ++i) {
    const double jitter = i % 2 == 0 ? 0.0 : 0.25;
    const TetMesh mesh = test_meshes::kuhn_cube(5, 1.0, jitter, static_cast<std::uint32_t>(i + 1));
    const ConvexPolygon blade = random_blade(rng, 5.0, 0.5 + 2.0 * (i % 5) / 4.0);
    const TetBvh bvh(mesh);
    const CutResult r = remove_cut(mesh, blade, {}, bvh.as_query());
    // Exactly the touched tets (against the clipping oracle, up to 1e-9 m either way).
    std::vector<char> removed(static_cast<std::size_t>(mesh.num_tets()), 0);
    double lost = 0.0;
    for (std::int32_t ti : r.delta.removed_tets) {
      removed[static_cast<std::size_t>(ti)] = 1;
      lost += mesh.rest_volume(ti);
    }
    for (std::int32_t ti = 0; ti < mesh.num_tets(); ++ti) {
      const Tet& t = mesh.tets[static_cast<std::size_t>(ti)];
      if (clip_oracle(mesh, t, blade, -1e-9)) {
        ASSERT_TRUE(removed[static_cast<std::size_t>(ti)]) << "cut " << i << " kept tet " << ti;
      } else if (!clip_oracle(mesh, t, blade, 1e-9)) {
        ASSERT_FALSE(removed[static_cast<std::size_t>(ti)]) << "cut " << i << " removed " << ti;
      }
    }
    EXPECT_EQ(r.stats.tets_removed, static_cast<std::int64_t>(r.delta.removed_tets.size()));
    EXPECT_TRUE(r.delta.added_tets.empty());
    EXPECT_TRUE(r.delta.added_nodes.empty());
    TetMesh after = mesh;
    TopologyDelta d = r.delta;
    apply(after, d);
    const double before_v = total_volume(mesh), after_v = total_volume(after);
    EXPECT_GT(lost, 0.0) << "cut " << i;
    EXPECT_NEAR(before_v - after_v, lost, 1e-12 * before_v) << "cut " << i;
    // The checker: structure must hold; the problems it may report are only the invariants
    // that do not apply to removal (volume, unreferenced nodes, boundary faces off the blade).
    const CutCheckReport rep = check_cut(mesh, after, blade);
    for (const std::string& p : rep.problems) {
      const bool expected = p.rfind("total volume changed", 0) == 0 || p.rfind("group ", 0) == 0 ||
                            p.rfind("the cut left", 0) == 0 || p.rfind("boundary face", 0) == 0;
      EXPECT_TRUE(expected) << "cut " << i << ": " << p;
    }
    const MeshCheckReport mc = check_mesh(after);
    EXPECT_TRUE(mc.problems.empty()) << "cut " << i << ": " << mc.problems.front();
    EXPECT_EQ(mc.overshared_faces, 0);
  }
}

// ---- snap ---------------------------------------------------------------------------------

struct Snapped {
  TetMesh after;
  CutResult result;
  SnapStats snap;
  CutCheckReport report;
};

Snapped snap_and_check(const TetMesh& mesh, const ConvexPolygon& blade) {
  Snapped s{mesh, {}, {}, {}};
  const TetBvh bvh(mesh);
  s.result = snap_cut(mesh, blade, {}, bvh.as_query(), &s.snap);
  apply(s.after, s.result.delta);
  CutCheckOptions co;
  co.geometry_tol_m = 1e-9;
  s.report = check_cut(mesh, s.after, blade, co);
  return s;
}

// The checker's problems that apply to snapping on a one-group box, and its boundary-face
// invariant point by point: every new boundary face's nodes and centroid lie on the blade
// (plane and polygon) or each on some old boundary face.
std::string snap_problems(const TetMesh& before, const Snapped& s, const ConvexPolygon& blade) {
  std::string out;
  for (const std::string& p : s.report.problems)
    if (p.rfind("the cut left", 0) != 0 && p.rfind("boundary face", 0) != 0)
      out.append(p).append("\n");
  const double tol = 1e-9;
  const FaceCensus fb = face_census(before), fa = face_census(s.after);
  auto key = [](Tri t) {
    std::sort(t.begin(), t.end());
    return t;
  };
  std::set<Tri> old;
  for (const BoundaryFace& f : fb.boundary) old.insert(key(f.nodes));
  auto on_old = [&](const Vec3& p) {
    for (const BoundaryFace& o : fb.boundary)
      if (geometry::point_triangle_distance(p, before.x[o.nodes[0]], before.x[o.nodes[1]],
                                            before.x[o.nodes[2]]) <= tol)
        return true;
    return false;
  };
  for (const BoundaryFace& f : fa.boundary) {
    if (old.contains(key(f.nodes))) continue;
    const Vec3 &a = s.after.x[f.nodes[0]], &b = s.after.x[f.nodes[1]], &c = s.after.x[f.nodes[2]];
    const Vec3 m = (a + b + c) / 3.0;
    bool blade_ok = true, old_ok = true;
    for (const Vec3* p : {&a, &b, &c, &m}) {
      blade_ok = blade_ok && std::abs(blade.signed_distance(*p)) <= tol &&
                 blade.contains_projection(*p, tol);
      old_ok = old_ok && on_old(*p);
    }
    if (!blade_ok && !old_ok) {
      out.append("boundary face (").append(std::to_string(f.nodes[0])).append(", ");
      out.append(std::to_string(f.nodes[1])).append(", ").append(std::to_string(f.nodes[2]));
      out.append(") lies neither on the blade nor on the old surface\n");
    }
  }
  return out;
}

// Two pieces, one on each side of the blade's plane.
void expect_two_sides(const Snapped& s, const ConvexPolygon& blade, int i) {
  const std::vector<std::int32_t> comp = tet_components(s.after);
  ASSERT_EQ(count_components(s.after), 2) << "cut " << i;
  const double tol = s.result.stats.tolerance_m + 1e-12;
  std::array<int, 2> side{0, 0};
  for (std::int32_t ti = 0; ti < s.after.num_tets(); ++ti)
    for (std::int32_t id : s.after.tets[static_cast<std::size_t>(ti)]) {
      const double phi = blade.signed_distance(s.after.x[id]);
      const auto c = static_cast<std::size_t>(comp[static_cast<std::size_t>(ti)]);
      if (phi > tol) side[c] |= 1;
      if (phi < -tol) side[c] |= 2;
    }
  EXPECT_TRUE((side[0] == 1 && side[1] == 2) || (side[0] == 2 && side[1] == 1))
      << "cut " << i << ": pieces on sides " << side[0] << ", " << side[1];
}

// A covering square through the middle of the 6^3 box, normal = axis + tilt * random.
ConvexPolygon covering_blade(std::mt19937& rng, int axis, double tilt) {
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  Vec3 n = Vec3::Zero();
  n[axis] = 1.0;
  n += tilt * Vec3(u(rng), u(rng), u(rng));
  const Vec3 c = Vec3::Constant(3.0) + 0.8 * Vec3(u(rng), u(rng), u(rng));
  return square(n, c, 20.0, u(rng));
}

TEST(SnapCut, NearAxisCoveringCutsSeparateIntoTwoPieces) {
  std::mt19937 rng(5);
  std::int64_t snapped = 0;
  const TetMesh mesh = test_meshes::kuhn_box(6, 6, 6, 1, 1.0);  // one group, flat sides
  const double v0 = total_volume(mesh);
  for (int i = 0; i < kCuts / 2; ++i) {
    const ConvexPolygon blade = covering_blade(rng, i % 3, 0.05);  // within 5 degrees
    const Snapped s = snap_and_check(mesh, blade);
    snapped += s.snap.nodes_snapped;
    ASSERT_EQ(s.result.stats.degenerate_tets, 0) << "cut " << i;
    const MeshCheckReport mc = check_mesh(s.after);
    ASSERT_TRUE(mc.problems.empty()) << "cut " << i << ": " << mc.problems.front();
    EXPECT_EQ(mc.overshared_faces, 0);
    EXPECT_EQ(mc.inverted_tets, 0);
    EXPECT_GT(mc.min_quality, 0.0);
    EXPECT_EQ(s.after.num_tets(), mesh.num_tets());  // snapping never subdivides
    EXPECT_EQ(snap_problems(mesh, s, blade), "") << "cut " << i;
    EXPECT_NEAR(total_volume(s.after), v0, 1e-12 * v0) << "cut " << i;
    ASSERT_EQ(s.snap.edges_unresolved, 0) << "cut " << i;
    expect_two_sides(s, blade, i);
  }
  EXPECT_GT(snapped, kCuts);  // the cuts did move nodes
}

TEST(SnapCut, SteepCoveringCutsStayValidAndMostlySeparate) {
  std::mt19937 rng(6);
  const TetMesh mesh = test_meshes::kuhn_box(6, 6, 6, 1, 1.0);
  const double v0 = total_volume(mesh);
  int separated = 0;
  double lost = 0.0;
  for (int i = 0; i < kCuts; ++i) {
    const ConvexPolygon blade = covering_blade(rng, i % 3, 0.35);  // up to about 30 degrees
    const Snapped s = snap_and_check(mesh, blade);
    ASSERT_EQ(s.result.stats.degenerate_tets, 0) << "cut " << i;
    const MeshCheckReport mc = check_mesh(s.after);
    ASSERT_TRUE(mc.problems.empty()) << "cut " << i << ": " << mc.problems.front();
    EXPECT_EQ(mc.overshared_faces, 0);
    // Volume and surface are not kept here: when no tangential move exists, a boundary node may
    // slide along a boundary edge off its flat side (SnapOptions, pass 3).
    lost = std::max(lost, (v0 - total_volume(s.after)) / v0);
    if (s.snap.edges_unresolved == 0) {
      expect_two_sides(s, blade, i);
      ++separated;
    } else {
      EXPECT_EQ(count_components(s.after), 1) << "cut " << i;  // welded where unresolved
    }
  }
  std::printf("snap: %d of %d steep covering cuts separated; largest volume change %.3g%%\n",
              separated, kCuts, 100.0 * lost);
  EXPECT_GE(separated, kCuts / 4);
}

TEST(SnapCut, PartialAndJitteredCutsKeepTheMeshValid) {
  std::mt19937 rng(9);
  for (int i = 0; i < kCuts; ++i) {
    const TetMesh mesh = test_meshes::kuhn_cube(5, 1.0, 0.25, static_cast<std::uint32_t>(i + 3));
    const ConvexPolygon blade = random_blade(rng, 5.0, 0.4 + 1.5 * (i % 4));
    const Snapped s = snap_and_check(mesh, blade);
    ASSERT_EQ(s.result.stats.degenerate_tets, 0) << "cut " << i;
    const MeshCheckReport mc = check_mesh(s.after);
    ASSERT_TRUE(mc.problems.empty()) << "cut " << i << ": " << mc.problems.front();
    EXPECT_EQ(mc.overshared_faces, 0);
    EXPECT_EQ(mc.inverted_tets, 0);
    // Every moved node lies on the blade's plane (current positions).
    const std::int32_t n0 = mesh.num_nodes();
    for (std::int32_t id = n0; id < s.after.num_nodes(); ++id)
      EXPECT_LE(std::abs(blade.signed_distance(s.after.x[id])), 1e-9) << "cut " << i;
    // The quality floor holds for every re-emitted tet that was above it before.
    for (std::size_t k = 0; k < s.result.delta.added_tets.size(); ++k) {
      const Tet& t = s.after.tets[static_cast<std::size_t>(s.result.delta.removed_tets[k])];
      const Tet& o = mesh.tets[static_cast<std::size_t>(s.result.delta.removed_tets[k])];
      const double q = tet_quality(s.after.rest[t[0]], s.after.rest[t[1]], s.after.rest[t[2]],
                                   s.after.rest[t[3]]);
      const double q0 =
          tet_quality(mesh.rest[o[0]], mesh.rest[o[1]], mesh.rest[o[2]], mesh.rest[o[3]]);
      EXPECT_GE(q, std::min(SnapOptions{}.min_quality, q0) - 1e-12) << "cut " << i;
    }
  }
}

TEST(SnapCut, PlaneThroughGridNodesOnlySplits) {
  // The plane x = 3 holds a whole layer of grid nodes: nothing moves, the layer is cloned.
  const TetMesh mesh = test_meshes::kuhn_box(6, 3, 3, 1, 1.0);
  const ConvexPolygon blade = square(Vec3::UnitX(), Vec3(3.0, 1.5, 1.5), 10.0);
  const Snapped s = snap_and_check(mesh, blade);
  EXPECT_EQ(s.snap.nodes_snapped, 0);
  EXPECT_EQ(s.snap.nodes_split, 16);  // the 4 x 4 nodes of the layer
  EXPECT_EQ(count_components(s.after), 2);
  EXPECT_EQ(snap_problems(mesh, s, blade), "");
}

TEST(SnapCut, FixedNodesNeverMove) {
  TetMesh mesh = test_meshes::kuhn_box(4, 4, 4, 1, 1.0);
  for (auto& f : mesh.fixed) f = 1;
  const ConvexPolygon blade = square(Vec3(1.0, 0.2, 0.1), Vec3(2.3, 2.0, 2.0), 10.0);
  SnapStats st;
  const CutResult r = snap_cut(mesh, blade, {}, {}, &st);
  EXPECT_EQ(st.nodes_snapped, 0);
  EXPECT_GT(st.snaps_refused, 0);
  EXPECT_EQ(st.edges_unresolved, st.crossing_edges);
  EXPECT_TRUE(r.delta.empty());
}

// ---- dispatch -----------------------------------------------------------------------------

TEST(CutMethod, NamesRoundTripAndDispatch) {
  for (CutMethod m : {CutMethod::kPattern, CutMethod::kRemove, CutMethod::kSnap})
    EXPECT_EQ(parse_cut_method(to_string(m)), m);
  EXPECT_FALSE(parse_cut_method("Pattern").has_value());
  EXPECT_FALSE(parse_cut_method("").has_value());
  const TetMesh mesh = test_meshes::kuhn_box(4, 2, 2, 1, 1.0);
  const ConvexPolygon blade = square(Vec3::UnitX(), Vec3(2.3, 1.0, 1.0), 5.0);
  const CutResult p = cut_with(CutMethod::kPattern, mesh, blade);
  const CutResult r = cut_with(CutMethod::kRemove, mesh, blade);
  const CutResult s = cut_with(CutMethod::kSnap, mesh, blade);
  EXPECT_GT(p.stats.tets_added, p.stats.tets_removed);  // subdivision adds tets
  EXPECT_EQ(r.stats.tets_added, 0);
  EXPECT_EQ(r.stats.tets_removed, 24);  // the 4 cubes of the column x in [2, 3]
  EXPECT_EQ(s.stats.tets_added, s.stats.tets_removed);
  EXPECT_GT(s.stats.nodes_added, 0);
}

}  // namespace
}  // namespace serosa::cutting
