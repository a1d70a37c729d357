#include "engine/geometry/ray_triangle.h"

#include <cmath>

namespace serosa::geometry {

bool ray_triangle(const Vec3& o, const Vec3& d, const Vec3& a, const Vec3& b, const Vec3& c,
                  double t_min, double t_max, RayTriangleHit& hit) {
  const Vec3 e1 = b - a;
  const Vec3 e2 = c - a;
  const Vec3 pv = d.cross(e2);
  const double det = e1.dot(pv);
  if (!(std::abs(det) > 1e-12 * e1.norm() * e2.norm() * d.norm())) return false;  // also NaN
  const double inv = 1.0 / det;
  const Vec3 tv = o - a;
  const double u = tv.dot(pv) * inv;
  if (u < 0.0 || u > 1.0) return false;
  const Vec3 qv = tv.cross(e1);
  const double v = d.dot(qv) * inv;
  if (v < 0.0 || u + v > 1.0) return false;
  const double t = e2.dot(qv) * inv;
  if (t < t_min || t > t_max) return false;
  hit.t = t;
  hit.bary = Vec3(1.0 - u - v, u, v);
  return true;
}

}  // namespace serosa::geometry
