// The branch's line on screen (render::OverlayData::branch): when the instructor took over and
// who drives what since, so that no one mistakes the recording for what the mouse does, e.g.
//   BRANCH at 0:05.2 (step 1041): the mouse drives grasper (left, active), clip-applier (right)
//   and endoscope (right button); the recording drives the rest. Tab: other hand, X: next
//   instrument
// (one line on screen). An empty hand is said ("no instrument (right)": X brings one in);
// instruments a hand let go of are named as staying where the mouse left them; once the recording
// has ended, the rest hold its last pose.
#pragma once

#include <cstddef>
#include <cstdint>
#include <string>

#include "engine/scene/scene.h"
#include "replay/mouse_takeover.h"

namespace serosa::replay {

struct BranchBannerInfo {
  std::uint64_t branch_step = 0;  ///< steps taken when it branched
  double dt_s = 0.0;              ///< the scene's step, s
  std::size_t active_hand = 0;    ///< the hand the mouse moves (PointerControl::active)
  bool recording_plays = true;    ///< the recording has steps left to drive the rest
};

/// The branch's line (above).
[[nodiscard]] std::string branch_banner(const Scene& scene, const MouseTakeover& takeover,
                                        const BranchBannerInfo& info);

/// Simulated time as the banner writes it, minutes:seconds to a tenth ("0:05.2", "12:00.0").
[[nodiscard]] std::string clock_time(double t_s);

}  // namespace serosa::replay
