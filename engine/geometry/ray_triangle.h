// Ray (and segment) versus triangle, Möller-Trumbore, with barycentric coordinates. Used by the
// collision BVH and by brute-force references in tests.
#pragma once

#include "engine/math.h"

namespace serosa::geometry {

/// Where a ray o + t d meets a triangle (a, b, c).
struct RayTriangleHit {
  double t = 0.0;            ///< ray parameter (m when |d| = 1; segment fraction for d = b - a)
  Vec3 bary = Vec3::Zero();  ///< barycentric coordinates of the hit point, each in [0, 1], sum 1
};

/// True when the ray o + t d (t in [t_min, t_max]) meets the closed triangle (a, b, c); `hit`
/// receives t and the barycentrics. Both sides count (no back-face culling). A ray parallel to
/// the triangle's plane (|det| <= 1e-12 |b - a| |c - a| |d|, which covers d = 0, degenerate
/// triangles and rays lying in the plane) never hits it: rays along an edge or a zero-length
/// segment report no hit on the triangles whose plane holds them.
[[nodiscard]] bool ray_triangle(const Vec3& o, const Vec3& d, const Vec3& a, const Vec3& b,
                                const Vec3& c, double t_min, double t_max, RayTriangleHit& hit);

}  // namespace serosa::geometry
