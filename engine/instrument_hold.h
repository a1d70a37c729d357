// Which hand holds an instrument, and whether it waits in its port. A trainee's two hands hold
// one instrument each; the others wait outside the body in their trocars until an exchange
// withdraws the held one through its trocar and inserts the chosen one through its own
// (haptics/haptics_stage.h for a live hand, a tool path's `hand` column for a script).
//
// Both travel in the upper half of ToolState::buttons (the lower half is the device's buttons,
// docs/rig-protocol.md), so the record stage records them with the pose, a replay reproduces
// every exchange, and the state hash covers them:
//   bits 16-17  the hand holding it: 0 none (played directly by a script or a replay), 1 the
//               left, 2 the right;
//   bit 18      in its port: withdrawn, out of the body. Stages ignore an instrument in its port:
//               it touches nothing, holds nothing, cuts, clips and coagulates nothing.
#pragma once

#include <cstdint>
#include <optional>

#include "engine/math.h"
#include "engine/scene/scene.h"
#include "engine/tool_state.h"

namespace serosa {

/// The handle button (the rig protocol's bit 2): an exchange.
inline constexpr std::uint32_t kExchangeButton = 1u << 2;
/// Bits 0-15: the device's own buttons.
inline constexpr std::uint32_t kDeviceButtons = 0xffffu;
inline constexpr std::uint32_t kHolderShift = 16;
inline constexpr std::uint32_t kHolderMask = 3u << kHolderShift;
inline constexpr std::uint32_t kInPortBit = 1u << 18;
/// How far outside its trocar a withdrawn instrument's tip waits, m.
inline constexpr double kPortOutsideM = 0.02;

/// The hand holding `tool`, if any.
[[nodiscard]] inline std::optional<Hand> holder(const ToolState& tool) noexcept {
  switch ((tool.buttons & kHolderMask) >> kHolderShift) {
    case 1:
      return Hand::kLeft;
    case 2:
      return Hand::kRight;
    default:
      return std::nullopt;
  }
}

/// Sets the hand holding `tool` (nullopt: none).
inline void set_holder(ToolState& tool, std::optional<Hand> hand) noexcept {
  const std::uint32_t v = !hand ? 0u : *hand == Hand::kLeft ? 1u : 2u;
  tool.buttons = (tool.buttons & ~kHolderMask) | (v << kHolderShift);
}

/// Whether `tool` waits in its port, out of the body.
[[nodiscard]] inline bool in_port(const ToolState& tool) noexcept {
  return (tool.buttons & kInPortBit) != 0;
}

inline void set_in_port(ToolState& tool, bool in) noexcept {
  tool.buttons = in ? (tool.buttons | kInPortBit) : (tool.buttons & ~kInPortBit);
}

/// An instrument waiting in its port: its tip kPortOutsideM outside the trocar `pivot_m` on the
/// port's axis `into_body` (unit, pointing into the body), its shaft along that axis, jaws closed,
/// held by no hand, in its port. time_s and tick are left 0.
[[nodiscard]] ToolState port_pose(const Vec3& pivot_m, const Vec3& into_body);

/// Where `tool` waits, given the instrument's pose `inside` (its shaft's line through the trocar
/// fixes the axis) and the trocar; a tool without a trocar waits 10 cm back along its shaft.
[[nodiscard]] ToolState port_pose(const Tool& tool, const ToolState& inside);

}  // namespace serosa
