#include "cutting/blade_sweep.h"

#include "cutting/planar_hull.h"

#include <algorithm>
#include <vector>

namespace serosa::cutting {

std::optional<ConvexPolygon> sweep_polygon(const BladeEdge& before, const BladeEdge& after,
                                           SweepWarnings& warnings, const SweepOptions& options) {
  if (!before.hinge.allFinite() || !before.tip.allFinite() || !after.hinge.allFinite() ||
      !after.tip.allFinite()) {
    ++warnings.non_finite;
    return std::nullopt;
  }
  const double len0 = (before.tip - before.hinge).norm();
  const double len1 = (after.tip - after.hinge).norm();
  if (!(len0 > options.min_length_m) || !(len1 > options.min_length_m)) {
    ++warnings.zero_length;
    return std::nullopt;
  }
  const double merge = options.merge_rel * std::max(len0, len1);

  // Corners in order around the sweep; a corner that did not move appears once.
  std::vector<Vec3> corners{before.hinge, before.tip};
  if ((after.tip - before.tip).norm() > merge) corners.push_back(after.tip);
  if ((after.hinge - before.hinge).norm() > merge) corners.push_back(after.hinge);
  if (corners.size() < 3) {
    ++warnings.zero_area;
    return std::nullopt;
  }

  // Best-fit plane: Newell normal through the centroid.
  Vec3 centroid = Vec3::Zero();
  for (const Vec3& c : corners) centroid += c;
  centroid /= static_cast<double>(corners.size());
  Vec3 newell = Vec3::Zero();
  double diameter = 0.0;
  for (std::size_t i = 0; i < corners.size(); ++i) {
    newell += (corners[i] - centroid).cross(corners[(i + 1) % corners.size()] - centroid);
    for (std::size_t j = i + 1; j < corners.size(); ++j)
      diameter = std::max(diameter, (corners[i] - corners[j]).norm());
  }
  // A crossed quad (bow-tie) can cancel Newell's normal: fall back to the largest corner
  // triangle's normal.
  Vec3 best = Vec3::Zero();
  for (std::size_t i = 0; i < corners.size(); ++i)
    for (std::size_t j = i + 1; j < corners.size(); ++j)
      for (std::size_t k = j + 1; k < corners.size(); ++k) {
        const Vec3 c = (corners[j] - corners[i]).cross(corners[k] - corners[i]);
        if (c.norm() > best.norm()) best = c;
      }
  if (!(best.norm() > 2.0 * options.min_area_rel * diameter * diameter)) {
    ++warnings.zero_area;
    return std::nullopt;
  }
  const Vec3 n = newell.norm() >= 0.5 * best.norm() ? newell.normalized() : best.normalized();
  double twist = 0.0;
  for (Vec3& c : corners) {
    const double off = n.dot(c - centroid);
    twist = std::max(twist, std::abs(off));
    c -= off * n;
  }
  if (twist > options.planar_rel * diameter) ++warnings.non_planar;

  // Convex hull in the plane (repairs a crossed quad), counter-clockwise about n.
  const Vec3 u = (corners[1] - corners[0]).normalized();
  const Vec3 v = n.cross(u);
  std::vector<Vec2> p2;
  for (const Vec3& c : corners) p2.emplace_back(u.dot(c - centroid), v.dot(c - centroid));
  std::vector<Vec3> outline;
  for (std::size_t i : hull2d(p2)) outline.push_back(corners[i]);
  auto poly = ConvexPolygon::make(std::move(outline), 1e-6);
  if (!poly || !(poly->area() > options.min_area_rel * diameter * diameter)) {
    ++warnings.zero_area;
    return std::nullopt;
  }
  return poly;
}

}  // namespace serosa::cutting
