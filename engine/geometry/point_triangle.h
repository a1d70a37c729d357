// Closest points on segments and triangles, the one implementation every floor uses (collision
// BVH, cut-face classification, cut checks and accuracy, tessellation distances, tool contact).
// Robust on degenerate input: zero-length segments, and zero-area or thin triangles (collinear
// or coincident corners, slivers), whose answer then comes from their edges.
#pragma once

#include "engine/math.h"

namespace serosa::geometry {

/// The point of triangle (a, b, c) nearest to p.
struct TrianglePoint {
  Vec3 point = Vec3::Zero();  ///< closest point, m: bary[0] a + bary[1] b + bary[2] c
  Vec3 bary = Vec3::Zero();   ///< barycentric coordinates, each in [0, 1], sum 1
  double dist2 = 0.0;         ///< squared distance |p - point|^2, m^2
};

/// Parameter t in [0, 1] of the point of segment [a, b] nearest to p (point = a + t (b - a));
/// 0 when a == b.
[[nodiscard]] double closest_segment_param(const Vec3& p, const Vec3& a, const Vec3& b);

/// The point of segment [a, b] (m) nearest to p (m).
[[nodiscard]] Vec3 closest_point_on_segment(const Vec3& p, const Vec3& a, const Vec3& b);

/// Closest point of triangle (a, b, c) (m) to p (m), by the Voronoi regions of Ericson,
/// "Real-Time Collision Detection", 5.1.5. Those region tests divide by the triangle's area and
/// lose precision as it vanishes, so a zero-area triangle (twice its area below 1e-12 of its
/// longest edge squared) is answered from its three edges alone, and a thin one (below 1e-4) by
/// the better of its edges and its face, projected in a frame on its longest edge. Every answer
/// is a point of the triangle, so the distance is never below the true one by more than
/// rounding; above it, by at most the inradius of a zero-area triangle.
[[nodiscard]] TrianglePoint closest_point_on_triangle(const Vec3& p, const Vec3& a, const Vec3& b,
                                                      const Vec3& c);

/// Distance (m) from p to triangle (a, b, c) (m): sqrt(closest_point_on_triangle(...).dist2).
[[nodiscard]] double point_triangle_distance(const Vec3& p, const Vec3& a, const Vec3& b,
                                             const Vec3& c);

}  // namespace serosa::geometry
