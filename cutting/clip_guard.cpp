#include "cutting/clip_guard.h"

#include <algorithm>
#include <cmath>

namespace serosa::cutting {

// A loop is its axis across the suture, reaching its cinched radius round it. The part of the
// clip's centre line within r of the polygon's plane, then whether any of it
// lies over the polygon grown by r.
bool polygon_meets_clip(const ConvexPolygon& polygon, const Clip& clip) {
  const double r = clip.reach_m() + kClipClearance;
  const Vec3 a = clip.end(0), b = clip.end(1);
  const double da = polygon.signed_distance(a), db = polygon.signed_distance(b);
  double t0 = 0.0, t1 = 1.0;
  if (da == db) {
    if (std::abs(da) > r) return false;
  } else {  // d(t) = da + t (db - da) within [-r, r]
    const double ta = (-r - da) / (db - da), tb = (r - da) / (db - da);
    t0 = std::max(t0, std::min(ta, tb));
    t1 = std::min(t1, std::max(ta, tb));
    if (t0 > t1) return false;
  }
  // Both ends are within r of the plane: a hair more keeps them there against rounding, so the
  // whole piece is tested against the grown polygon.
  const double tol = r * (1.0 + 1e-9);
  return polygon.intersect_segment(a + t0 * (b - a), a + t1 * (b - a), tol).has_value();
}

bool polygon_meets_clips(const ConvexPolygon& polygon, const std::vector<Clip>& clips) {
  return std::any_of(clips.begin(), clips.end(),
                     [&](const Clip& c) { return polygon_meets_clip(polygon, c); });
}

}  // namespace serosa::cutting
