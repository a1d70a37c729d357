#include "engine/geometry/point_triangle.h"

#include <algorithm>
#include <array>
#include <cmath>

namespace serosa::geometry {
namespace {

// Below these ratios of |ab x ac|^2 to (longest edge)^4 a triangle is degenerate (edges only) or
// thin (closest_on_thin). Unsquared: |ab x ac| below 1e-12 and 1e-4 of the longest edge squared.
constexpr double kDegenerate2 = 1e-24;
constexpr double kThin2 = 1e-8;

TrianglePoint make(const Vec3& p, const Vec3& a, const Vec3& b, const Vec3& c, double u, double v,
                   double w) {
  TrianglePoint r;
  r.bary = Vec3(u, v, w);
  r.point = u * a + v * b + w * c;
  r.dist2 = (p - r.point).squaredNorm();
  return r;
}

// Best of the triangle's three edges.
TrianglePoint closest_on_edges(const Vec3& p, const Vec3& a, const Vec3& b, const Vec3& c) {
  const double tab = closest_segment_param(p, a, b);
  const double tbc = closest_segment_param(p, b, c);
  const double tca = closest_segment_param(p, c, a);
  TrianglePoint best = make(p, a, b, c, 1.0 - tab, tab, 0.0);
  const TrianglePoint e2 = make(p, a, b, c, 0.0, 1.0 - tbc, tbc);
  const TrianglePoint e3 = make(p, a, b, c, tca, 0.0, 1.0 - tca);
  if (e2.dist2 < best.dist2) best = e2;
  if (e3.dist2 < best.dist2) best = e3;
  return best;
}

// Ericson's region tests (the triangle must have area).
TrianglePoint closest_by_regions(const Vec3& p, const Vec3& a, const Vec3& b, const Vec3& c) {
  const Vec3 ab = b - a;
  const Vec3 ac = c - a;
  // Vertex region a.
  const Vec3 ap = p - a;
  const double d1 = ab.dot(ap);
  const double d2 = ac.dot(ap);
  if (d1 <= 0.0 && d2 <= 0.0) return make(p, a, b, c, 1.0, 0.0, 0.0);
  // Vertex region b.
  const Vec3 bp = p - b;
  const double d3 = ab.dot(bp);
  const double d4 = ac.dot(bp);
  if (d3 >= 0.0 && d4 <= d3) return make(p, a, b, c, 0.0, 1.0, 0.0);
  // Edge region ab.
  const double vc = d1 * d4 - d3 * d2;
  if (vc <= 0.0 && d1 >= 0.0 && d3 <= 0.0) {
    const double t = d1 / (d1 - d3);
    return make(p, a, b, c, 1.0 - t, t, 0.0);
  }
  // Vertex region c.
  const Vec3 cp = p - c;
  const double d5 = ab.dot(cp);
  const double d6 = ac.dot(cp);
  if (d6 >= 0.0 && d5 <= d6) return make(p, a, b, c, 0.0, 0.0, 1.0);
  // Edge region ac.
  const double vb = d5 * d2 - d1 * d6;
  if (vb <= 0.0 && d2 >= 0.0 && d6 <= 0.0) {
    const double t = d2 / (d2 - d6);
    return make(p, a, b, c, 1.0 - t, 0.0, t);
  }
  // Edge region bc.
  const double va = d3 * d6 - d5 * d4;
  if (va <= 0.0 && (d4 - d3) >= 0.0 && (d5 - d6) >= 0.0) {
    const double t = (d4 - d3) / ((d4 - d3) + (d5 - d6));
    return make(p, a, b, c, 0.0, 1.0 - t, t);
  }
  // Face region.
  const double denom = 1.0 / (va + vb + vc);
  const double v = vb * denom;
  const double w = vc * denom;
  return make(p, a, b, c, 1.0 - v - w, v, w);
}

// A thin triangle: the better of its edges and the face answer, found in an orthonormal frame on
// its longest edge. That frame tilts out of the plane by ~1e-16 of (length / height) about the
// longest edge only, so the projection's height over that edge (at most the triangle's) is off
// by that angle times the query's distance, not times the triangle's length as in the region
// tests, whose products of dot products cancel. A projection found outside the triangle leaves
// the edges' answer, off by at most the inradius.
TrianglePoint closest_on_thin(const Vec3& p, const Vec3& a, const Vec3& b, const Vec3& c) {
  const TrianglePoint edges = closest_on_edges(p, a, b, c);
  const std::array<const Vec3*, 3> v{&a, &b, &c};
  int i = 0;  // longest edge (v[i], v[j]); v[k] the opposite corner
  double len2 = -1.0;
  for (int e = 0; e < 3; ++e) {
    const double l2 = (*v[(e + 1) % 3] - *v[e]).squaredNorm();
    if (l2 > len2) {
      len2 = l2;
      i = e;
    }
  }
  const int j = (i + 1) % 3, k = (i + 2) % 3;
  const Vec3& o = *v[i];
  const double len = std::sqrt(len2);
  const Vec3 e1 = (*v[j] - o) / len;
  const Vec3 w = *v[k] - o;
  const double cx = w.dot(e1);
  const Vec3 up = w - cx * e1;
  const double h = up.norm();
  if (!(h > 0.0)) return edges;
  const Vec3 r = p - o;
  std::array<double, 3> bary{};
  bary[k] = r.dot(up / h) / h;
  bary[j] = (r.dot(e1) - bary[k] * cx) / len;
  bary[i] = 1.0 - bary[j] - bary[k];
  if (!(bary[0] >= 0.0 && bary[1] >= 0.0 && bary[2] >= 0.0)) return edges;
  const TrianglePoint face = make(p, a, b, c, bary[0], bary[1], bary[2]);
  return face.dist2 < edges.dist2 ? face : edges;
}

}  // namespace

double closest_segment_param(const Vec3& p, const Vec3& a, const Vec3& b) {
  const Vec3 ab = b - a;
  const double len2 = ab.squaredNorm();
  if (!(len2 > 0.0)) return 0.0;
  return std::clamp((p - a).dot(ab) / len2, 0.0, 1.0);
}

Vec3 closest_point_on_segment(const Vec3& p, const Vec3& a, const Vec3& b) {
  return a + closest_segment_param(p, a, b) * (b - a);
}

TrianglePoint closest_point_on_triangle(const Vec3& p, const Vec3& a, const Vec3& b,
                                        const Vec3& c) {
  const Vec3 ab = b - a;
  const Vec3 ac = c - a;
  const double area2 = ab.cross(ac).squaredNorm();
  const double scale2 = std::max({ab.squaredNorm(), ac.squaredNorm(), (c - b).squaredNorm()});
  const double scale4 = scale2 * scale2;
  if (!(area2 > kDegenerate2 * scale4)) return closest_on_edges(p, a, b, c);
  if (area2 < kThin2 * scale4) return closest_on_thin(p, a, b, c);
  return closest_by_regions(p, a, b, c);
}

double point_triangle_distance(const Vec3& p, const Vec3& a, const Vec3& b, const Vec3& c) {
  return std::sqrt(closest_point_on_triangle(p, a, b, c).dist2);
}

}  // namespace serosa::geometry
