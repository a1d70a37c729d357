// A hook cautery: an L-shaped electrode at the tip of an insulated shaft. While its pedal is
// pressed (a rig's cautery pedal, a script's buttons column, the trainee's key), tissue the
// electrode's crook passes through is divided and the band around its path coagulated
// (cutting/cutting_stage.h).
#pragma once

#include <cstdint>

#include "engine/math.h"
#include "engine/tool_geometry.h"

namespace serosa {

/// A tool input's buttons bit: the cautery pedal pressed (the rig protocol's bit 1).
inline constexpr std::uint32_t kPedalButton = 1u << 1;
/// Length of the hook's crook, from the tip along the tool's local +x, m.
inline constexpr double kHookCrook = 0.003;
/// Tissue within this distance of the live crook is coagulated, m.
inline constexpr double kCoagulationRadius = 0.0015;

/// The live part of the electrode: the crook from the tip along local +x, m.
struct HookSegment {
  Vec3 a = Vec3::Zero();  ///< the tip, m
  Vec3 b = Vec3::Zero();  ///< the crook's end, m
};

[[nodiscard]] inline HookSegment hook_segment(const ToolState& tool) {
  const ToolFrame f = tool_frame(tool);
  return {f.tip, f.tip + kHookCrook * f.side};
}

/// True when the input holds the cautery pedal down.
[[nodiscard]] inline bool pedal_down(const ToolState& tool) {
  return (tool.buttons & kPedalButton) != 0;
}

}  // namespace serosa
