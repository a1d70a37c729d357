// Triangulating a tet's section where the blade's edge crosses it (partial cuts): a small
// constrained triangulation of a convex planar point set, in the blade's 2D plane coordinates.
#pragma once

#include <array>
#include <span>
#include <vector>

#include <Eigen/Core>

namespace serosa::cutting {

/// Triangulates the convex hull of `points` (2D, m) using every point as a vertex and every
/// segment of `constraints` (index pairs) as an edge. Greedy: required segments first, then the
/// other segments shortest first, each kept when it passes through no other point and crosses no
/// kept segment (a maximal non-crossing set triangulates the hull). `eps` (m) is the distance
/// under which a point lies on a segment. Meant for a dozen points (O(n^4)). Returns the
/// triangles (indices, counter-clockwise); the caller checks that their areas add up.
/// @param points       (n) distinct 2D points, m
/// @param constraints  (c) index pairs that must be edges (non-crossing, through no point)
[[nodiscard]] std::vector<std::array<int, 3>> triangulate_section(
    std::span<const Eigen::Vector2d> points, std::span<const std::array<int, 2>> constraints,
    double eps);

/// Signed area (m^2) of the 2D triangle (a, b, c): positive when counter-clockwise.
[[nodiscard]] inline double area2d(const Eigen::Vector2d& a, const Eigen::Vector2d& b,
                                   const Eigen::Vector2d& c) {
  return 0.5 * ((b - a).x() * (c - a).y() - (b - a).y() * (c - a).x());
}

}  // namespace serosa::cutting
