// Planar geometry for swept blade regions: the best-fit plane of a point cloud, the convex hull
// of points in a plane, and clipping a convex outline by a half-plane. A closing stroke's swept
// surface is a cloud of blade positions; cut as one polygon, it is their hull in the plane that
// fits them best (cutting/scissors_stroke.h).
#pragma once

#include <optional>
#include <span>
#include <vector>

#include "engine/math.h"

namespace serosa::cutting {

using Vec2 = Eigen::Vector2d;

/// A plane through `centroid` (m) with unit `normal`, and the in-plane basis (u, v), u x v = n.
struct PlaneFit {
  Vec3 centroid = Vec3::Zero();
  Vec3 normal = Vec3::UnitZ();
  Vec3 u = Vec3::UnitX();
  Vec3 v = Vec3::UnitY();
  double deviation_m = 0.0;  ///< largest distance of the fitted points from the plane, m

  [[nodiscard]] Vec2 to_plane(const Vec3& p) const {
    return {u.dot(p - centroid), v.dot(p - centroid)};
  }
  [[nodiscard]] Vec3 to_world(const Vec2& q) const { return centroid + q.x() * u + q.y() * v; }
};

/// Least-squares plane of `points` (m): the normal is the direction of least spread (principal
/// components). std::nullopt when the points span no plane (fewer than 3, or collinear within
/// `min_width_rel` times their extent), or a coordinate is not finite. The normal is turned to
/// the side of `towards` (any vector; ignored when zero).
[[nodiscard]] std::optional<PlaneFit> fit_plane(std::span<const Vec3> points,
                                                const Vec3& towards = Vec3::Zero(),
                                                double min_width_rel = 1e-6);

/// Indices of the convex hull of `points`, counter-clockwise (Andrew's monotone chain); collinear
/// and repeated points are dropped.
[[nodiscard]] std::vector<std::size_t> hull2d(const std::vector<Vec2>& points);

/// The convex outline `poly` (counter-clockwise) cut to the half-plane {q : n . (q - at) >= 0}.
[[nodiscard]] std::vector<Vec2> clip_halfplane(const std::vector<Vec2>& poly, const Vec2& at,
                                               const Vec2& n);

/// The convex outline `subject` cut to the counter-clockwise convex outline `clip`: their
/// intersection (Sutherland-Hodgman).
[[nodiscard]] std::vector<Vec2> clip_convex(std::vector<Vec2> subject,
                                            const std::vector<Vec2>& clip);

/// Area of a simple outline (m^2; positive counter-clockwise).
[[nodiscard]] double signed_area(const std::vector<Vec2>& poly);

}  // namespace serosa::cutting
