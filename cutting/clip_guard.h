// Scissors never cut through a clip: closing on one, the blades meet titanium and stop. The
// cutting stage leaves a stroke uncut when its polygon meets a placed clip (engine/clip.h).
#pragma once

#include <vector>

#include "cutting/convex_polygon.h"
#include "engine/clip.h"

namespace serosa::cutting {

/// Clearance kept from a clip's legs, m: a polygon closer than this to the clip's centre line
/// (beyond its legs' half width) meets it.
inline constexpr double kClipClearance = 5e-4;

/// True when `polygon` passes within kClipHalfWidth + kClipClearance of `clip`'s centre line.
[[nodiscard]] bool polygon_meets_clip(const ConvexPolygon& polygon, const Clip& clip);

/// True when `polygon` meets any of `clips`.
[[nodiscard]] bool polygon_meets_clips(const ConvexPolygon& polygon,
                                       const std::vector<Clip>& clips);

}  // namespace serosa::cutting
