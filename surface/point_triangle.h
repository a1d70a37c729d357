// Closest point on a triangle to a point (Ericson, "Real-Time Collision Detection", 5.1.5), with
// barycentric coordinates. Used by the collision BVH and by the cut-face classifier.
#pragma once

#include "engine/math.h"

namespace serosa::surface {

/// The point of triangle (a, b, c) nearest to p.
struct TrianglePoint {
  Vec3 point = Vec3::Zero();  ///< closest point, m: bary[0] a + bary[1] b + bary[2] c
  Vec3 bary = Vec3::Zero();   ///< barycentric coordinates, each in [0, 1], sum 1
  double dist2 = 0.0;         ///< squared distance |p - point|^2, m^2
};

/// Closest point of triangle (a, b, c) (m) to p (m). Degenerate triangles (collinear or
/// coincident corners) are handled: the answer is then the closest point on their edges.
[[nodiscard]] TrianglePoint closest_point_on_triangle(const Vec3& p, const Vec3& a, const Vec3& b,
                                                      const Vec3& c);

}  // namespace serosa::surface
