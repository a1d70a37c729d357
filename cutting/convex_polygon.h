// ConvexPolygon: a convex planar polygon in world coordinates (m), the shape a blade sweeps
// between two solver steps. Validation, its plane, 2D inclusion and segment intersection.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "engine/math.h"

namespace serosa::cutting {

/// Where a segment meets a polygon (see ConvexPolygon::intersect_segment).
struct SegmentHit {
  /// Transverse: the segment crosses the plane at one parameter t0 (= t1), inside the polygon.
  /// Coplanar: the segment lies in the plane; [t0, t1] is its part inside the polygon.
  enum class Kind { kTransverse, kCoplanar } kind = Kind::kTransverse;
  double t0 = 0.0;  ///< segment parameter in [0, 1] (point = a + t (b - a))
  double t1 = 0.0;  ///< segment parameter in [0, 1], t1 >= t0
};

/// A convex planar polygon with at least three vertices, in world coordinates (m).
/// The normal follows the vertex order (counter-clockwise seen from the normal's tip).
/// Immutable after construction.
class ConvexPolygon {
 public:
  /// Validates and builds the polygon. Throws std::invalid_argument naming the problem when there
  /// are fewer than 3 points, a non-finite coordinate, a zero-length edge, zero area, points off
  /// the plane by more than planarity_tol * diameter, or a non-convex (or self-winding) outline.
  /// Consecutive collinear points are allowed.
  /// @param points         (k >= 3) vertices in order, m
  /// @param planarity_tol  relative to the polygon's diameter (dimensionless)
  explicit ConvexPolygon(std::vector<Vec3> points, double planarity_tol = 1e-6);

  /// Non-throwing form: std::nullopt and the reason in *why (when why is not null).
  static std::optional<ConvexPolygon> make(std::vector<Vec3> points, double planarity_tol = 1e-6,
                                           std::string* why = nullptr);

  [[nodiscard]] const std::vector<Vec3>& points() const { return m_points; }
  [[nodiscard]] std::size_t size() const { return m_points.size(); }
  /// Unit normal of the plane.
  [[nodiscard]] const Vec3& normal() const { return m_normal; }
  /// Plane offset d (m): the plane is {p : normal . p = d}.
  [[nodiscard]] double offset() const { return m_offset; }
  /// Area (m^2) and diameter (largest vertex distance, m).
  [[nodiscard]] double area() const { return m_area; }
  [[nodiscard]] double diameter() const { return m_diameter; }
  /// Axis-aligned bounding box of the vertices (m).
  [[nodiscard]] const Vec3& box_min() const { return m_box_min; }
  [[nodiscard]] const Vec3& box_max() const { return m_box_max; }

  /// Signed distance of p to the plane, m (positive on the normal's side).
  [[nodiscard]] double signed_distance(const Vec3& p) const { return m_normal.dot(p) - m_offset; }
  /// In-plane coordinates (m) of p's orthogonal projection, in the basis (u, v) with u x v = n.
  [[nodiscard]] Eigen::Vector2d to_plane(const Vec3& p) const;
  /// Smallest signed distance (m) from p's projection to the polygon's edge lines: positive
  /// inside, zero on the boundary, negative outside (exactly the distance outside near edges).
  [[nodiscard]] double inside_margin(const Vec3& p) const;
  /// True when p's projection onto the plane lies in the polygon grown by tol (m).
  /// Meant for points on the plane; the distance to the plane is not checked here.
  [[nodiscard]] bool contains_projection(const Vec3& p, double tol = 0.0) const {
    return inside_margin(p) >= -tol;
  }
  /// Intersection of segment [a, b] with the polygon (grown by tol, m, both in plane distance and
  /// in-plane inclusion). std::nullopt when they do not meet.
  [[nodiscard]] std::optional<SegmentHit> intersect_segment(const Vec3& a, const Vec3& b,
                                                            double tol = 0.0) const;

 private:
  ConvexPolygon() = default;
  static std::optional<std::string> build(std::vector<Vec3> points, double planarity_tol,
                                          ConvexPolygon& out);

  std::vector<Vec3> m_points;              ///< (k) vertices, m
  std::vector<Eigen::Vector2d> m_points2;  ///< (k) in-plane coordinates, counter-clockwise
  Vec3 m_normal = Vec3::UnitZ();
  Vec3 m_u = Vec3::UnitX();  ///< in-plane basis, u x v = normal
  Vec3 m_v = Vec3::UnitY();
  double m_offset = 0.0;
  double m_area = 0.0;
  double m_diameter = 0.0;
  Vec3 m_box_min = Vec3::Zero();
  Vec3 m_box_max = Vec3::Zero();
};

}  // namespace serosa::cutting
