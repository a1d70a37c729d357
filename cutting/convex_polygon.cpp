#include "cutting/convex_polygon.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <limits>
#include <numbers>
#include <stdexcept>
#include <string>

namespace serosa::cutting {
namespace {

double cross2(const Eigen::Vector2d& a, const Eigen::Vector2d& b) {
  return a.x() * b.y() - a.y() * b.x();
}

// Four significant digits, any magnitude (std::to_string prints 6e-8 as "0.000000").
std::string short_number(double v) {
  std::array<char, 32> buf{};
  std::snprintf(buf.data(), buf.size(), "%.4g", v);
  return buf.data();
}

}  // namespace

std::optional<std::string> ConvexPolygon::build(std::vector<Vec3> points, double planarity_tol,
                                                ConvexPolygon& out) {
  const std::size_t k = points.size();
  if (k < 3) return "ConvexPolygon: needs at least 3 points, got " + std::to_string(k);
  for (std::size_t i = 0; i < k; ++i)
    if (!points[i].allFinite())
      return "ConvexPolygon: point " + std::to_string(i) + " has a non-finite coordinate";

  // Diameter and bounding box.
  double diameter = 0.0;
  Vec3 lo = points[0], hi = points[0];
  for (std::size_t i = 0; i < k; ++i) {
    lo = lo.cwiseMin(points[i]);
    hi = hi.cwiseMax(points[i]);
    for (std::size_t j = i + 1; j < k; ++j)
      diameter = std::max(diameter, (points[i] - points[j]).norm());
  }
  if (!(diameter > 0.0)) return std::string("ConvexPolygon: all points coincide (zero size)");
  for (std::size_t i = 0; i < k; ++i)
    if ((points[(i + 1) % k] - points[i]).norm() <= 1e-12 * diameter)
      return "ConvexPolygon: edge " + std::to_string(i) + " has zero length (repeated point)";

  // Newell's normal: twice the vector area, robust for any planar polygon.
  Vec3 centroid = Vec3::Zero();
  for (const Vec3& p : points) centroid += p;
  centroid /= static_cast<double>(k);
  Vec3 newell = Vec3::Zero();
  for (std::size_t i = 0; i < k; ++i)
    newell += (points[i] - centroid).cross(points[(i + 1) % k] - centroid);
  const double area = 0.5 * newell.norm();
  if (!(area > 1e-12 * diameter * diameter))
    return std::string(
        "ConvexPolygon: zero area (points are collinear, or their order crosses itself)");
  const Vec3 n = newell.normalized();
  const double d = n.dot(centroid);

  // Planarity.
  for (std::size_t i = 0; i < k; ++i) {
    const double off = std::abs(n.dot(points[i]) - d);
    if (off > planarity_tol * diameter)
      return "ConvexPolygon: point " + std::to_string(i) + " is " + short_number(off) +
             " m off the plane (tolerance " + short_number(planarity_tol * diameter) + " m)";
  }

  // In-plane basis and coordinates.
  const Vec3 u = (points[1] - points[0] - n * n.dot(points[1] - points[0])).normalized();
  const Vec3 v = n.cross(u);
  std::vector<Eigen::Vector2d> p2(k);
  for (std::size_t i = 0; i < k; ++i) p2[i] = Eigen::Vector2d(u.dot(points[i]), v.dot(points[i]));

  // Convexity: every turn left (or straight) and total turning exactly one revolution.
  double turning = 0.0;
  for (std::size_t i = 0; i < k; ++i) {
    const Eigen::Vector2d e0 = p2[(i + 1) % k] - p2[i];
    const Eigen::Vector2d e1 = p2[(i + 2) % k] - p2[(i + 1) % k];
    const double c = cross2(e0, e1);
    if (c < -1e-12 * e0.norm() * e1.norm())
      return "ConvexPolygon: not convex (turns the wrong way at point " +
             std::to_string((i + 1) % k) + ")";
    turning += std::atan2(c, e0.dot(e1));
  }
  if (std::abs(turning - 2.0 * std::numbers::pi) > 1e-6)
    return std::string("ConvexPolygon: outline winds more than once (not a simple polygon)");

  out.m_points = std::move(points);
  out.m_points2 = std::move(p2);
  out.m_normal = n;
  out.m_u = u;
  out.m_v = v;
  out.m_offset = d;
  out.m_area = area;
  out.m_diameter = diameter;
  out.m_box_min = lo;
  out.m_box_max = hi;
  return std::nullopt;
}

ConvexPolygon::ConvexPolygon(std::vector<Vec3> points, double planarity_tol) {
  if (auto why = build(std::move(points), planarity_tol, *this)) throw std::invalid_argument(*why);
}

std::optional<ConvexPolygon> ConvexPolygon::make(std::vector<Vec3> points, double planarity_tol,
                                                 std::string* why) {
  ConvexPolygon poly;
  if (auto err = build(std::move(points), planarity_tol, poly)) {
    if (why != nullptr) *why = *err;
    return std::nullopt;
  }
  return poly;
}

Eigen::Vector2d ConvexPolygon::to_plane(const Vec3& p) const {
  return Eigen::Vector2d(m_u.dot(p), m_v.dot(p));
}

double ConvexPolygon::inside_margin(const Vec3& p) const {
  const Eigen::Vector2d q = to_plane(p);
  double margin = std::numeric_limits<double>::infinity();
  const std::size_t k = m_points2.size();
  for (std::size_t i = 0; i < k; ++i) {
    const Eigen::Vector2d& a = m_points2[i];
    const Eigen::Vector2d e = m_points2[(i + 1) % k] - a;
    margin = std::min(margin, cross2(e, q - a) / e.norm());
  }
  return margin;
}

std::optional<SegmentHit> ConvexPolygon::intersect_segment(const Vec3& a, const Vec3& b,
                                                           double tol) const {
  const double da = signed_distance(a);
  const double db = signed_distance(b);
  if (std::abs(da) <= tol && std::abs(db) <= tol) {
    // Coplanar: clip the parameter interval against every edge's half-plane (Cyrus-Beck).
    const Eigen::Vector2d qa = to_plane(a), qb = to_plane(b);
    double t0 = 0.0, t1 = 1.0;
    const std::size_t k = m_points2.size();
    for (std::size_t i = 0; i < k; ++i) {
      const Eigen::Vector2d& p = m_points2[i];
      const Eigen::Vector2d e = m_points2[(i + 1) % k] - p;
      const double fa = cross2(e, qa - p) / e.norm() + tol;  // >= 0 inside the grown polygon
      const double fb = cross2(e, qb - p) / e.norm() + tol;
      if (fa < 0.0 && fb < 0.0) return std::nullopt;
      if (fa < 0.0) t0 = std::max(t0, fa / (fa - fb));
      if (fb < 0.0) t1 = std::min(t1, fa / (fa - fb));
    }
    if (t0 > t1) return std::nullopt;
    return SegmentHit{SegmentHit::Kind::kCoplanar, t0, t1};
  }
  if ((da > tol && db > tol) || (da < -tol && db < -tol)) return std::nullopt;
  double t = 0.0;
  if (std::abs(da) <= tol)
    t = 0.0;
  else if (std::abs(db) <= tol)
    t = 1.0;
  else
    t = da / (da - db);
  if (!contains_projection(a + t * (b - a), tol)) return std::nullopt;
  return SegmentHit{SegmentHit::Kind::kTransverse, t, t};
}

}  // namespace serosa::cutting
