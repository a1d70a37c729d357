// engine/geometry/point_triangle.h: property tests on thousands of triangles, well shaped, thin
// (needles and caps down to a height of 1e-14 of their length), exactly degenerate (collinear,
// two or three coincident corners), tiny (1e-9 and 1e-12 m far from the origin) and large.
// Two references: (1) a query built with a known answer (a point q of the triangle and a
// direction in its normal cone there, so q is the nearest point at the chosen distance), in a
// frame where the triangle's plane is exact, then rotated and moved; (2) brute force: the
// distance to a dense sampling of the triangle (an upper bound of the true distance, and a lower
// bound within the sampling's resolution).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <random>
#include <vector>

#include "engine/geometry/point_triangle.h"

namespace serosa::geometry {
namespace {

std::mt19937_64& rng() {
  static std::mt19937_64 r(20240611);
  return r;
}
double uni(double lo = 0.0, double hi = 1.0) {
  return std::uniform_real_distribution<double>(lo, hi)(rng());
}

// In-plane (z = 0) unit normal of edge (u, v), pointing away from the third corner o.
Vec3 outward(const Vec3& u, const Vec3& v, const Vec3& o) {
  const Vec3 e = v - u;
  Vec3 m(e.y(), -e.x(), 0.0);
  if (m.dot(o - u) > 0.0) m = -m;
  return m.normalized();
}

// A query with a known answer, in the triangle's own frame (plane z = 0).
struct Case {
  std::array<Vec3, 3> tri;  ///< corners, m
  Vec3 p = Vec3::Zero();    ///< query, m
  double dist = 0.0;        ///< the nearest distance, m
};

// Non-degenerate triangle (a, b, c) in z = 0: the nearest point q is an interior point, a point
// inside an edge or a corner (kind 0, 1, 2), p = q + d dir with dir in the normal cone at q.
Case known_answer(const std::array<Vec3, 3>& t, int kind, double d) {
  const Vec3 z(0.0, 0.0, uni() < 0.5 ? 1.0 : -1.0);
  Vec3 q, dir;
  if (kind == 0) {
    double u = uni(), v = uni();
    if (u + v > 1.0) u = 1.0 - u, v = 1.0 - v;
    q = t[0] + u * (t[1] - t[0]) + v * (t[2] - t[0]);
    dir = z;
  } else if (kind == 1) {
    const int e = static_cast<int>(uni(0.0, 3.0)) % 3;
    const Vec3 &u = t[e], &v = t[(e + 1) % 3], &o = t[(e + 2) % 3];
    q = u + uni(0.01, 0.99) * (v - u);
    dir = uni() * outward(u, v, o) + uni() * z;
  } else {
    const int k = static_cast<int>(uni(0.0, 3.0)) % 3;
    const Vec3 &v = t[k], &n1 = t[(k + 1) % 3], &n2 = t[(k + 2) % 3];
    q = v;
    dir = uni() * outward(v, n1, n2) + uni() * outward(n2, v, n1) + uni() * z;
  }
  if (dir.norm() < 1e-3) dir = z;
  return {t, q + d * dir.normalized(), d};
}

// Collinear corners (on the x axis, any of them coincident): the triangle is the segment
// [min x, max x]; q on it, dir perpendicular to it (or outward past an end).
Case known_answer_collinear(const std::array<double, 3>& xs, double d) {
  const double lo = std::min({xs[0], xs[1], xs[2]}), hi = std::max({xs[0], xs[1], xs[2]});
  const double phi = uni(0.0, 6.283185307179586);
  Vec3 dir(0.0, std::cos(phi), std::sin(phi));
  Vec3 q(lo + uni() * (hi - lo), 0.0, 0.0);
  if (uni() < 0.3) {  // past an end
    const bool at_hi = uni() < 0.5;
    q = Vec3(at_hi ? hi : lo, 0.0, 0.0);
    dir += Vec3(at_hi ? uni() : -uni(), 0.0, 0.0);
  }
  return {{Vec3(xs[0], 0.0, 0.0), Vec3(xs[1], 0.0, 0.0), Vec3(xs[2], 0.0, 0.0)},
          q + d * dir.normalized(),
          d};
}

// A random rotation and translation (offset up to `far` m) applied to the case.
Case moved(const Case& c, double far) {
  Quat r(uni(-1, 1), uni(-1, 1), uni(-1, 1), uni(-1, 1));
  r.normalize();
  const Vec3 off(uni(-far, far), uni(-far, far), uni(-far, far));
  Case out = c;
  for (Vec3& v : out.tri) v = r * v + off;
  out.p = r * c.p + off;
  return out;
}

// The checks every answer must pass: barycentrics in [0, 1] summing to 1, the point their
// combination, dist2 its squared distance.
void expect_consistent(const TrianglePoint& r, const Case& c, double tol) {
  EXPECT_GE(r.bary.minCoeff(), 0.0);
  EXPECT_LE(r.bary.maxCoeff(), 1.0);
  EXPECT_NEAR(r.bary.sum(), 1.0, 1e-12);
  const Vec3 comb = r.bary[0] * c.tri[0] + r.bary[1] * c.tri[1] + r.bary[2] * c.tri[2];
  EXPECT_LE((comb - r.point).norm(), tol);
  EXPECT_NEAR(r.dist2, (c.p - r.point).squaredNorm(), 1e-12 * (r.dist2 + tol * tol));
}

// The implementation on case c0 moved up to `far` m away: its distance within rel_tol of the
// coordinates' scale, and a consistent answer.
void check(const Case& c0, double far, double rel_tol, const char* what) {
  const Case c = moved(c0, far);
  const TrianglePoint r = closest_point_on_triangle(c.p, c.tri[0], c.tri[1], c.tri[2]);
  double scale = far + c0.dist;
  for (const Vec3& v : c0.tri) scale = std::max(scale, v.norm());
  // Moving the corners rounds them by ~1e-16 scale: the true distance moves by as much.
  const double tol = rel_tol * scale;
  const double err = std::abs(std::sqrt(r.dist2) - c.dist);
  ASSERT_TRUE(std::isfinite(r.dist2)) << what;
  ASSERT_LE(err, tol) << what << ": distance " << std::sqrt(r.dist2) << ", expected " << c.dist;
  expect_consistent(r, c, 1e-12 * scale);
  EXPECT_EQ(point_triangle_distance(c.p, c.tri[0], c.tri[1], c.tri[2]), std::sqrt(r.dist2));
}

TEST(PointTriangle, KnownAnswersOnWellShapedTriangles) {
  for (int it = 0; it < 4000; ++it) {
    const std::array<Vec3, 3> t{Vec3(uni(-1, 1), uni(-1, 1), 0.0),
                                Vec3(uni(-1, 1), uni(-1, 1), 0.0),
                                Vec3(uni(-1, 1), uni(-1, 1), 0.0)};
    if (std::abs((t[1] - t[0]).cross(t[2] - t[0]).z()) < 0.05) continue;  // well shaped only
    check(known_answer(t, it % 3, std::pow(10.0, uni(-6.0, 1.0))), 1.0, 1e-13, "well shaped");
  }
}

// Needles (apex over the base) and caps (apex beyond an end) of relative height 1e-2 .. 1e-14.
// The region tests alone were off by up to 66 % of the length here; the worst error seen (3e5
// queries per height) is 1.1e-11 of the length, at heights near 1e-7.
TEST(PointTriangle, KnownAnswersOnThinTriangles) {
  for (const double h : {1e-2, 1e-4, 1e-5, 1e-6, 1e-8, 1e-10, 1e-12, 1e-14}) {
    for (int it = 0; it < 1500; ++it) {
      const double s = uni(-0.5, 1.5);  // apex position along the base: cap when outside [0, 1]
      const std::array<Vec3, 3> t{Vec3(0.0, 0.0, 0.0), Vec3(1.0, 0.0, 0.0), Vec3(s, h, 0.0)};
      check(known_answer(t, it % 3, std::pow(10.0, uni(-6.0, 1.0))), 1.0, 1e-10, "thin");
    }
  }
}

TEST(PointTriangle, KnownAnswersOnDegenerateTriangles) {
  for (int it = 0; it < 3000; ++it) {
    std::array<double, 3> xs{uni(-1, 1), uni(-1, 1), uni(-1, 1)};
    if (it % 4 == 1) xs[1] = xs[0];          // two corners coincide
    if (it % 4 == 2) xs[2] = xs[1] = xs[0];  // a point
    const double d = std::pow(10.0, uni(-6.0, 1.0));
    check(known_answer_collinear(xs, d), 1.0, 1e-13, "collinear");
  }
  // A corner repeated with the third elsewhere, off the axis: still a segment, written as
  // (a, a, c), (a, c, a) and (c, a, a).
  for (int it = 0; it < 1000; ++it) {
    const Vec3 a(uni(-1, 1), uni(-1, 1), uni(-1, 1)), c(uni(-1, 1), uni(-1, 1), uni(-1, 1));
    const Vec3 p(uni(-2, 2), uni(-2, 2), uni(-2, 2));
    const double ref = (p - closest_point_on_segment(p, a, c)).norm();
    EXPECT_NEAR(point_triangle_distance(p, a, a, c), ref, 1e-14);
    EXPECT_NEAR(point_triangle_distance(p, a, c, a), ref, 1e-14);
    EXPECT_NEAR(point_triangle_distance(p, c, a, a), ref, 1e-14);
    EXPECT_NEAR(point_triangle_distance(p, a, a, a), (p - a).norm(), 0.0);
  }
}

// Tiny triangles (a nanometre and a picometre) at the origin and 1 m away, and a large one: the
// error stays at the rounding of the coordinates (1 m away, the corners and the query are
// rounded by ~1e-16 m when moved there).
TEST(PointTriangle, KnownAnswersOnTinyAndLargeTriangles) {
  struct Run {
    double size, far, rel_tol;
  };
  for (const Run run : {Run{1e-12, 0.0, 1e-13}, Run{1e-9, 0.0, 1e-13}, Run{1e-12, 1.0, 4e-15},
                        Run{1e-9, 1.0, 4e-15}, Run{1e3, 0.0, 1e-13}}) {
    for (int it = 0; it < 1000; ++it) {
      const std::array<Vec3, 3> t{Vec3(0.0, 0.0, 0.0), Vec3(run.size, 0.0, 0.0),
                                  Vec3(uni(0.0, 1.0) * run.size, uni(0.1, 1.0) * run.size, 0.0)};
      const double d = run.size * std::pow(10.0, uni(-3.0, 3.0));
      check(known_answer(t, it % 3, d), run.far, run.rel_tol, "tiny or large");
    }
  }
}

// Brute force: the distance to a dense sampling of the triangle (barycentric grid plus its
// edges). The answer is never above it (beyond rounding), and never below it by more than the
// sampling's resolution. Random triangles of every shape, degenerate ones included.
TEST(PointTriangle, MatchesDenseSampling) {
  constexpr int kGrid = 48, kEdge = 400;
  for (int it = 0; it < 1500; ++it) {
    std::array<Vec3, 3> t{Vec3(uni(-1, 1), uni(-1, 1), uni(-1, 1)),
                          Vec3(uni(-1, 1), uni(-1, 1), uni(-1, 1)),
                          Vec3(uni(-1, 1), uni(-1, 1), uni(-1, 1))};
    if (it % 5 == 1) t[2] = t[0] + uni(-2, 2) * (t[1] - t[0]);  // collinear
    if (it % 5 == 2) t[2] = t[1];                               // coincident
    if (it % 5 == 3) t[2] = t[0] + uni() * (t[1] - t[0]) + 1e-9 * Vec3(uni(), uni(), uni());
    const Vec3 p(uni(-2, 2), uni(-2, 2), uni(-2, 2));
    double sampled = std::numeric_limits<double>::infinity();
    for (int i = 0; i <= kGrid; ++i)
      for (int j = 0; i + j <= kGrid; ++j) {
        const double u = static_cast<double>(i) / kGrid, v = static_cast<double>(j) / kGrid;
        sampled = std::min(sampled, (p - (t[0] + u * (t[1] - t[0]) + v * (t[2] - t[0]))).norm());
      }
    for (int e = 0; e < 3; ++e)
      for (int k = 0; k <= kEdge; ++k) {
        const Vec3& a = t[e];
        const Vec3& b = t[(e + 1) % 3];
        const double s = static_cast<double>(k) / kEdge;
        sampled = std::min(sampled, (p - (a + s * (b - a))).norm());
      }
    double diam = 0.0;
    for (int e = 0; e < 3; ++e) diam = std::max(diam, (t[e] - t[(e + 1) % 3]).norm());
    const TrianglePoint r = closest_point_on_triangle(p, t[0], t[1], t[2]);
    const double d = std::sqrt(r.dist2);
    ASSERT_LE(d, sampled + 1e-13) << it;
    ASSERT_GE(d, sampled - diam / kGrid) << it;
    expect_consistent(r, {t, p, d}, 1e-13);
  }
}

TEST(PointTriangle, SegmentsIncludingZeroLength) {
  for (int it = 0; it < 2000; ++it) {
    const Vec3 a(uni(-1, 1), uni(-1, 1), uni(-1, 1));
    const Vec3 b = it % 4 == 0 ? a : Vec3(uni(-1, 1), uni(-1, 1), uni(-1, 1));
    const Vec3 p(uni(-2, 2), uni(-2, 2), uni(-2, 2));
    const double t = closest_segment_param(p, a, b);
    ASSERT_GE(t, 0.0);
    ASSERT_LE(t, 1.0);
    const Vec3 q = closest_point_on_segment(p, a, b);
    EXPECT_LE((q - (a + t * (b - a))).norm(), 1e-15);
    double sampled = std::numeric_limits<double>::infinity();
    for (int k = 0; k <= 1000; ++k)
      sampled = std::min(sampled, (p - (a + k / 1000.0 * (b - a))).norm());
    EXPECT_LE((p - q).norm(), sampled + 1e-14);
    EXPECT_GE((p - q).norm(), sampled - (b - a).norm() / 1000.0);
  }
  EXPECT_EQ(closest_segment_param(Vec3(1, 2, 3), Vec3::Zero(), Vec3::Zero()), 0.0);
}

}  // namespace
}  // namespace serosa::geometry
