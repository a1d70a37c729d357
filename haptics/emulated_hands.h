// The scripted hands that play an emulated rig's handles over a tool path with a hand column
// (haptics/rig_hand_script.h), planned against the instruments the handles can take
// (haptics/hand_rack.h), and checked: each instrument a hand takes must be one of the rack's, and
// the exchange that brings it in must give it (the next waiting in scene order).
#pragma once

#include <array>
#include <optional>

#include "engine/scene/scene.h"
#include "engine/scene/tool_path.h"
#include "haptics/hand_rack.h"
#include "haptics/rig_hand_script.h"

namespace serosa::haptics {

/// One plan per handle that holds an instrument. Throws InputError naming the path's file, the
/// hand, the time and the instrument when the hand column gives a hand a tool that is not one of
/// the rack's instruments, or one that an exchange there would not bring in.
[[nodiscard]] std::array<std::optional<RigHand>, kHandles> emulated_hands(const Scene& scene,
                                                                          const HandRack& rack,
                                                                          const ToolPath& path);

}  // namespace serosa::haptics
