#include "surface/point_triangle.h"

#include <algorithm>

namespace serosa::surface {
namespace {

// Closest point of segment [a, b] to p, as the weight t of b (point = a + t (b - a)).
double segment_param(const Vec3& p, const Vec3& a, const Vec3& b) {
  const Vec3 ab = b - a;
  const double len2 = ab.squaredNorm();
  if (len2 <= 0.0) return 0.0;
  return std::clamp((p - a).dot(ab) / len2, 0.0, 1.0);
}

TrianglePoint make(const Vec3& p, const Vec3& a, const Vec3& b, const Vec3& c, double u, double v,
                   double w) {
  TrianglePoint r;
  r.bary = Vec3(u, v, w);
  r.point = u * a + v * b + w * c;
  r.dist2 = (p - r.point).squaredNorm();
  return r;
}

// Degenerate triangle: best of its three edges.
TrianglePoint closest_on_edges(const Vec3& p, const Vec3& a, const Vec3& b, const Vec3& c) {
  const double tab = segment_param(p, a, b);
  const double tbc = segment_param(p, b, c);
  const double tca = segment_param(p, c, a);
  TrianglePoint best = make(p, a, b, c, 1.0 - tab, tab, 0.0);
  const TrianglePoint e2 = make(p, a, b, c, 0.0, 1.0 - tbc, tbc);
  const TrianglePoint e3 = make(p, a, b, c, tca, 0.0, 1.0 - tca);
  if (e2.dist2 < best.dist2) best = e2;
  if (e3.dist2 < best.dist2) best = e3;
  return best;
}

}  // namespace

TrianglePoint closest_point_on_triangle(const Vec3& p, const Vec3& a, const Vec3& b,
                                        const Vec3& c) {
  const Vec3 ab = b - a;
  const Vec3 ac = c - a;
  // Degenerate (zero-area) triangle: Ericson's region test divides by the area.
  const double area2 = ab.cross(ac).squaredNorm();
  const double scale2 = std::max({ab.squaredNorm(), ac.squaredNorm(), (c - b).squaredNorm()});
  if (!(area2 > 1e-24 * scale2 * scale2)) return closest_on_edges(p, a, b, c);

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

}  // namespace serosa::surface
