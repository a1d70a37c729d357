// An endoloop: a pre-tied suture loop with a sliding knot at the end of a knot-pusher tube. The
// loop is passed over the appendix and cinched at its base, where it ligates the tissue it
// encircles (contact/clip_stage.h). Of the two ways to secure the base, the default scene takes a
// loop rather than a stapler: it is what most trainers teach and what costs least, and it needs
// no staple line: the scissors transect beyond it (the stapler variant: engine/stapler.h).
//
// The tool's jaw channel is the loop's size: open (jaw_rad >= kLoopArmRad) it is a ring of
// radius kLoopRadius in the plane normal to the shaft through the tool's tip, its knot at the tip
// and its centre kLoopRadius along the tool's local +x, so the pusher stays beside the tissue the
// ring goes round. Closing the channel to kLoopCloseRad pushes the knot down: the loop cinches.
#pragma once

#include <algorithm>

#include "engine/math.h"
#include "engine/tool_geometry.h"
#include "engine/tool_state.h"

namespace serosa {

/// Radius of the open loop, m (a 2 cm loop, the usual pre-tied size).
inline constexpr double kLoopRadius = 0.01;
/// The loop is out and open when the jaw channel reaches this, rad ...
inline constexpr double kLoopArmRad = 0.3;
/// ... and cinched when it then closes to this, rad.
inline constexpr double kLoopCloseRad = 0.05;

/// The open loop's ring: its centre, unit axis (the shaft direction) and the unit direction from
/// the centre to the knot.
struct LoopRing {
  Vec3 centre = Vec3::Zero();  ///< m
  Vec3 axis = Vec3::UnitZ();
  Vec3 to_knot = -Vec3::UnitX();
  double radius_m = kLoopRadius;  ///< shrinks as the channel closes, m
};

[[nodiscard]] inline LoopRing loop_ring(const ToolState& tool) {
  const ToolFrame f = tool_frame(tool);
  const double open = std::clamp(tool.jaw_rad / kLoopArmRad, 0.1, 1.0);
  LoopRing r;
  r.radius_m = kLoopRadius * open;
  r.centre = f.tip + r.radius_m * f.side;
  r.axis = f.forward;
  r.to_knot = -f.side;
  return r;
}

}  // namespace serosa
