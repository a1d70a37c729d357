// Scissors never cut through a ligature: closing on a clip, the blades meet titanium and stop;
// on a loop's knot, they would cut the suture the base depends on. The cutting stage leaves a
// stroke uncut when its polygon meets a placed clip or loop (engine/clip.h).
#pragma once

#include <vector>

#include "cutting/convex_polygon.h"
#include "engine/clip.h"

namespace serosa::cutting {

/// Clearance kept from a clip's legs, m: a polygon closer than this to the clip's centre line
/// (beyond its legs' half width) meets it.
inline constexpr double kClipClearance = 5e-4;

/// True when `polygon` passes within clip.reach_m() + kClipClearance of `clip`'s centre line
/// (a loop's: its axis across the suture).
[[nodiscard]] bool polygon_meets_clip(const ConvexPolygon& polygon, const Clip& clip);

/// True when `polygon` meets any of `clips`.
[[nodiscard]] bool polygon_meets_clips(const ConvexPolygon& polygon,
                                       const std::vector<Clip>& clips);

}  // namespace serosa::cutting
