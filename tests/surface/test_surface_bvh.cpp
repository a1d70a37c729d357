// SurfaceBvh (engine/geometry/surface_bvh.h) against brute force over every face: closest point,
// ray and segment queries, thousands of random and degenerate ones, after build, refit and local
// updates.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <random>
#include <set>

#include "cutting/convex_polygon.h"
#include "cutting/cut_mesh.h"
#include "engine/geometry/point_triangle.h"
#include "engine/geometry/ray_triangle.h"
#include "engine/geometry/surface_bvh.h"
#include "engine/geometry/tet_extent.h"
#include "engine/topology_delta.h"
#include "surface/extract_surface.h"
#include "surface/update_surface.h"
#include "surface_fixtures.h"

namespace serosa::surface {
namespace {

using geometry::closest_point_on_triangle;
using geometry::ClosestHit;
using geometry::ray_triangle;
using geometry::RayHit;
using geometry::RayTriangleHit;
using geometry::SurfaceBvh;
using geometry::TrianglePoint;
using test_meshes::kuhn_box;

#if defined(__SANITIZE_ADDRESS__)
constexpr int kQueries = 600;
#else
constexpr int kQueries = 3000;
#endif

constexpr double kInf = std::numeric_limits<double>::infinity();

const Vec3& at(const TetMesh& m, std::int32_t v) { return m.x[static_cast<std::size_t>(v)]; }

// ---- brute force: the same primitives, every face, smaller slot wins ties ----

std::optional<ClosestHit> bf_closest(const SurfaceMesh& s, const TetMesh& m, const Vec3& p) {
  std::optional<ClosestHit> best;
  double best_d2 = kInf;
  for (std::int32_t i = 0; i < s.num_faces(); ++i) {
    const Tri& f = s.faces[i];
    const TrianglePoint q = closest_point_on_triangle(p, at(m, f[0]), at(m, f[1]), at(m, f[2]));
    if (!best || q.dist2 < best_d2) {
      best_d2 = q.dist2;
      best = ClosestHit{i, q.point, q.bary, std::sqrt(q.dist2)};
    }
  }
  return best;
}

std::vector<RayHit> bf_hits(const SurfaceMesh& s, const TetMesh& m, const Vec3& o, const Vec3& d,
                            double t_max) {
  std::vector<RayHit> hits;
  for (std::int32_t i = 0; i < s.num_faces(); ++i) {
    const Tri& f = s.faces[i];
    RayTriangleHit h;
    if (ray_triangle(o, d, at(m, f[0]), at(m, f[1]), at(m, f[2]), 0.0, t_max, h))
      hits.push_back(RayHit{i, h.t, h.bary});
  }
  std::sort(hits.begin(), hits.end(), [](const RayHit& p, const RayHit& q) {
    return std::tie(p.t, p.face) < std::tie(q.t, q.face);
  });
  return hits;
}

// ---- comparisons ----

void expect_closest(const SurfaceBvh& bvh, const SurfaceMesh& s, const TetMesh& m, const Vec3& p) {
  const auto got = bvh.closest_point(m.x, p);
  const auto want = bf_closest(s, m, p);
  ASSERT_EQ(got.has_value(), want.has_value());
  if (!want) return;
  ASSERT_EQ(got->distance, want->distance) << "p " << p.transpose();
  // The smaller slot among equally near faces (ties are common: vertices, edges).
  const Tri& f = s.faces[got->face];
  const TrianglePoint q = closest_point_on_triangle(p, at(m, f[0]), at(m, f[1]), at(m, f[2]));
  ASSERT_EQ(std::sqrt(q.dist2), got->distance);
  ASSERT_EQ(got->face, want->face) << "p " << p.transpose();
  ASSERT_LT((got->point -
             (got->bary[0] * at(m, f[0]) + got->bary[1] * at(m, f[1]) + got->bary[2] * at(m, f[2])))
                .norm(),
            1e-12);
}

void expect_ray(const SurfaceBvh& bvh, const SurfaceMesh& s, const TetMesh& m, const Vec3& o,
                const Vec3& d, double t_max) {
  const auto got = bvh.raycast(m.x, o, d, t_max);
  const auto want = bf_hits(s, m, o, d, t_max);
  ASSERT_EQ(got.has_value(), !want.empty()) << "o " << o.transpose() << " d " << d.transpose();
  if (want.empty()) return;
  ASSERT_EQ(got->t, want.front().t);
  ASSERT_EQ(got->face, want.front().face);
  ASSERT_EQ(got->bary, want.front().bary);
}

void expect_segment(const SurfaceBvh& bvh, const SurfaceMesh& s, const TetMesh& m, const Vec3& a,
                    const Vec3& b) {
  std::vector<RayHit> got;
  bvh.segment_all(m.x, a, b, got);
  const auto want = bf_hits(s, m, a, b - a, 1.0);
  ASSERT_EQ(got.size(), want.size()) << "a " << a.transpose() << " b " << b.transpose();
  for (std::size_t i = 0; i < got.size(); ++i) {
    ASSERT_EQ(got[i].face, want[i].face);
    ASSERT_EQ(got[i].t, want[i].t);
  }
  const auto first = bvh.segment_first(m.x, a, b);
  ASSERT_EQ(first.has_value(), !want.empty());
  if (first) {
    ASSERT_EQ(first->face, want.front().face);
  }
}

/// Thousands of random and degenerate queries of each kind.
void check_queries(const SurfaceBvh& bvh, const SurfaceMesh& s, const TetMesh& m, std::mt19937& rng,
                   int n) {
  ASSERT_EQ(bvh.num_faces(), s.num_faces());
  Vec3 lo, hi;
  geometry::point_box(m.x, lo, hi);
  const Vec3 c = 0.5 * (lo + hi), e = hi - lo;
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  const double big = 2.0 * e.maxCoeff();
  for (int i = 0; i < n; ++i) {
    const Vec3 p(c.x() + 0.8 * e.x() * u(rng), c.y() + 0.8 * e.y() * u(rng),
                 c.z() + 0.8 * e.z() * u(rng));
    const Vec3 q(c.x() + 0.8 * e.x() * u(rng), c.y() + 0.8 * e.y() * u(rng),
                 c.z() + 0.8 * e.z() * u(rng));
    const Vec3 dir(u(rng), u(rng), u(rng));
    const Tri& f = s.faces[rng() % s.faces.size()];
    const auto k = static_cast<std::size_t>(rng() % 3);
    const Vec3 ea = at(m, f[k]);  // an edge (ea, eb) of a face; ea is also a surface vertex
    const Vec3 eb = at(m, f[(k + 1) % 3]);
    const Vec3 mid = 0.5 * (ea + eb);
    // Closest point: random, exactly on a vertex, on an edge's midpoint.
    expect_closest(bvh, s, m, p);
    expect_closest(bvh, s, m, ea);
    expect_closest(bvh, s, m, mid);
    // Rays: random; from a vertex along an edge; axis-aligned (zero direction components) aimed
    // at a vertex; through a vertex from outside; limited t.
    expect_ray(bvh, s, m, p, dir, kInf);
    expect_ray(bvh, s, m, ea, eb - ea, kInf);
    Vec3 axis(0.0, 0.0, 0.0);
    axis[static_cast<int>(rng() % 3)] = rng() % 2 ? 1.0 : -1.0;
    expect_ray(bvh, s, m, ea - big * axis, axis, kInf);
    const Vec3 far = q + Vec3(big, big, big);
    expect_ray(bvh, s, m, far, ea - far, kInf);
    expect_ray(bvh, s, m, p, dir, 0.3 * e.minCoeff());
    // Segments: random; zero length (on the surface and off it); along an edge.
    expect_segment(bvh, s, m, p, q);
    expect_segment(bvh, s, m, ea, ea);
    expect_segment(bvh, s, m, p, p);
    expect_segment(bvh, s, m, ea, eb);
    if (::testing::Test::HasFatalFailure()) return;
  }
}

/// A curved, bumpy organ: a grid ball with noise, in current positions.
TetMesh ball(std::mt19937& rng, int n) {
  TetMesh m = kuhn_box(n, n, n, 2, 2.0 / n);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  for (Vec3& p : m.x) {
    p -= Vec3(1, 1, 1);
    if (p.norm() > 0.0) p *= p.cwiseAbs().maxCoeff() / p.norm();
    p += 0.02 * Vec3(u(rng), u(rng), u(rng));
  }
  return m;
}

TEST(SurfaceBvh, QueriesMatchBruteForceOnAFlatSidedBox) {
  std::mt19937 rng(1);
  const TetMesh m = kuhn_box(6, 5, 4, 2);  // axis-aligned flat sides: many exact ties
  const SurfaceMesh s = extract_surface(m);
  SurfaceBvh bvh;
  bvh.build(s, m.x);
  check_queries(bvh, s, m, rng, kQueries);
}

TEST(SurfaceBvh, QueriesMatchBruteForceOnABumpyBallAfterRefit) {
  std::mt19937 rng(2);
  TetMesh m = ball(rng, 8);
  const SurfaceMesh s = extract_surface(m);
  SurfaceBvh bvh;
  bvh.build(s, m.x);
  check_queries(bvh, s, m, rng, kQueries / 3);
  // Deform a lot (the boxes must follow), refit, query again.
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  for (Vec3& p : m.x)
    p = Vec3(1.5 * p.x(), p.y() + 0.3 * p.x() * p.x(), p.z()) + 0.05 * Vec3(u(rng), u(rng), u(rng));
  bvh.refit(m.x);
  check_queries(bvh, s, m, rng, kQueries / 3);
}

TEST(SurfaceBvh, EmptySurfaceAnswersNothing) {
  const TetMesh m;
  const SurfaceMesh s;
  SurfaceBvh bvh;
  bvh.build(s, m.x);
  EXPECT_FALSE(bvh.closest_point(m.x, Vec3::Zero()).has_value());
  EXPECT_FALSE(bvh.raycast(m.x, Vec3::Zero(), Vec3::UnitX()).has_value());
  std::vector<RayHit> hits{RayHit{}};
  bvh.segment_all(m.x, Vec3::Zero(), Vec3::UnitX(), hits);
  EXPECT_TRUE(hits.empty());
}

TEST(SurfaceBvh, MaxDistanceAndBadInput) {
  const TetMesh m = kuhn_box(2, 2, 2, 1, 1.0);
  const SurfaceMesh s = extract_surface(m);
  SurfaceBvh bvh;
  bvh.build(s, m.x);
  EXPECT_FALSE(bvh.closest_point(m.x, Vec3(1, 1, 5), 2.9).has_value());
  const auto hit = bvh.closest_point(m.x, Vec3(1, 1, 5), 3.1);
  ASSERT_TRUE(hit.has_value());
  EXPECT_DOUBLE_EQ(hit->distance, 3.0);
  EXPECT_THROW(bvh.build(s, std::span<const Vec3>(m.x).first(3)), std::invalid_argument);
  const std::vector<std::int32_t> bad{s.num_faces()};
  EXPECT_THROW(bvh.update(s, bad, m.x), std::invalid_argument);
}

/// Removes up to k random tets, or splits random tets at their centroid.
TopologyDelta random_delta(std::mt19937& rng, const TetMesh& m) {
  std::set<std::int32_t> ids;
  for (int i = 0; i < 3 && m.num_tets() > 0; ++i)
    ids.insert(static_cast<std::int32_t>(rng() % static_cast<unsigned>(m.num_tets())));
  TopologyDelta d;
  d.removed_tets.assign(ids.begin(), ids.end());
  if (rng() % 2) {
    for (std::int32_t r : d.removed_tets) {
      const Tet& t = m.tets[static_cast<std::size_t>(r)];
      NodeParent p;
      p.count = 4;
      p.nodes = t;
      p.weights = {0.25, 0.25, 0.25, 0.25};
      const auto c = m.num_nodes() + static_cast<std::int32_t>(d.added_nodes.size());
      d.added_nodes.push_back(p);
      for (int i = 0; i < 4; ++i) {
        Tet q = t;
        q[static_cast<std::size_t>(i)] = c;
        d.added_tets.push_back(q);
        d.added_groups.push_back(m.group[static_cast<std::size_t>(r)]);
      }
    }
  }
  return d;
}

// Local updates (update_surface's changed slots) give the same answers as a rebuild and as brute
// force, after carving, splitting and real cuts, with deformation and refits in between.
TEST(SurfaceBvh, LocalUpdateEqualsRebuild) {
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  TetMesh m = ball(rng, 6);
  SurfaceMesh s = extract_surface(m);
  FaceTable table = build_face_table(m, s);
  SurfaceBvh bvh;
  bvh.build(s, m.x);
  std::vector<std::int32_t> changed;
  for (int step = 0; step < 40; ++step) {
    TopologyDelta d;
    if (step % 8 == 7) {  // a real cut through the whole organ
      const Vec3 n = Vec3(u(rng), u(rng), u(rng)).normalized();
      const Vec3 c = 0.5 * Vec3(u(rng), u(rng), u(rng));
      const Vec3 a = n.unitOrthogonal(), b = n.cross(a);
      d = cutting::cut_mesh(m, cutting::ConvexPolygon({c - 3 * a - 3 * b, c + 3 * a - 3 * b,
                                                       c + 3 * a + 3 * b, c - 3 * a + 3 * b}))
              .delta;
    } else {
      d = random_delta(rng, m);
    }
    apply(m, d);
    update_surface(s, table, m, d, nullptr, &changed);
    for (Vec3& p : m.x) p += 0.002 * Vec3(u(rng), u(rng), u(rng));  // the solver moves nodes
    bvh.update(s, changed, m.x);
    SurfaceBvh rebuilt;
    rebuilt.build(s, m.x);
    ASSERT_EQ(bvh.num_faces(), s.num_faces());
    // Same answers as the rebuild (and both as brute force) on random queries.
    for (int q = 0; q < 100; ++q) {
      const Vec3 p = 1.3 * Vec3(u(rng), u(rng), u(rng));
      const Vec3 dir(u(rng), u(rng), u(rng));
      const auto c1 = bvh.closest_point(m.x, p), c2 = rebuilt.closest_point(m.x, p);
      ASSERT_EQ(c1.has_value(), c2.has_value());
      if (c1) {
        ASSERT_EQ(c1->face, c2->face) << "step " << step;
        ASSERT_EQ(c1->distance, c2->distance);
      }
      const auto r1 = bvh.raycast(m.x, p, dir), r2 = rebuilt.raycast(m.x, p, dir);
      ASSERT_EQ(r1.has_value(), r2.has_value()) << "step " << step;
      if (r1) {
        ASSERT_EQ(r1->face, r2->face);
        ASSERT_EQ(r1->t, r2->t);
      }
    }
    if (step % 20 == 19) check_queries(bvh, s, m, rng, 100);
    if (::testing::Test::HasFatalFailure()) return;
  }
  // Local updates keep the tree usable: its depth stays within a few times a rebuild's.
  SurfaceBvh rebuilt;
  rebuilt.build(s, m.x);
  EXPECT_LE(bvh.depth(), 4 * rebuilt.depth());
}

}  // namespace
}  // namespace serosa::surface
