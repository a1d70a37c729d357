// What a scripted hand does with a rig handle over a tool path whose hand column names the hands
// (engine/scene/tool_path.h): the emulated rig's handles play the procedure as a trainee would,
// each instrument in turn.
//
// A handle follows the path of the instrument its hand holds, carried from that instrument's
// port to the handle's own trocar (haptics/hand_rack.h: the rig's joints are the same whichever
// instrument it holds). Where the hand column gives the hand another instrument, the hand
// exchanges it as a trainee does on the rig: it presses the handle button (kExchangeButton) for
// kPressHoldS, so the haptics stage puts the old instrument in its port; meanwhile it draws the
// handle back at kHandWithdrawSpeedMS to kDrawnBackM from its trocar, turning it towards the new
// instrument's path, and holds it there kDrawnBackHoldS, so the stage sees it drawn back and lets
// the new instrument follow it; then it pushes the handle in at kHandEntrySpeedMS until it meets
// the new instrument's path. Before its first exchange a handle follows the instrument it holds
// first, whatever the hand column says.
//
// The stage gives the handle the next instrument waiting in scene order; emulated_hands
// (haptics/emulated_hands.h) refuses a path whose hands take them in another order.
#pragma once

#include <cstddef>
#include <cstdint>
#include <optional>
#include <vector>

#include "engine/instrument_hold.h"
#include "engine/scene/tool_path.h"
#include "haptics/hand_rack.h"
#include "haptics/trocar_kinematics.h"

namespace serosa::haptics {

/// Insertion the hand draws a handle back to for an exchange, m (< kEntryDepthM).
inline constexpr double kDrawnBackM = 0.015;
/// How long the hand holds the handle button down, s of the path's time: thirty solver steps,
/// so that a step sees it even when the machine is so loaded that the loop or the emulated
/// firmware misses a tenth of a second (each step sees only the newest packet).
inline constexpr double kPressHoldS = 0.15;
/// How long it holds the handle drawn back, s of the path's time: as long, for the same reason.
inline constexpr double kDrawnBackHoldS = 0.15;
/// How fast the hand draws a handle back, m/s (a quick pull: the trocar's drag about 2 N).
inline constexpr double kHandWithdrawSpeedMS = 1.0;
/// How fast the hand pushes a new instrument in through its port, m/s.
inline constexpr double kHandEntrySpeedMS = 0.5;

/// From t_s on, the hand holds path tool `tool` (index into ToolPath::tools).
struct HandChange {
  double t_s = 0.0;
  std::size_t tool = 0;
};

/// The instruments `hand` takes over `path`, in time order: each row whose hand column gives the
/// tool to `hand` where the tool's row before did not.
[[nodiscard]] std::vector<HandChange> hand_changes(const ToolPath& path, Hand hand);

/// One rig handle played by a scripted hand.
struct RigHand {
  std::optional<std::size_t> first_tool;  ///< path tool the handle holds first (none: idle)
  Trocar trocar;                          ///< the handle's own trocar
  std::vector<HandChange> exchanges;      ///< each change to another instrument, time order
  /// (path tools) each path tool's port carried to the handle's trocar (identity for none)
  std::vector<TrocarMap> to_handle;
};

/// Handle plan for `hand`: `first_tool` first, then the instruments the hand column gives it.
[[nodiscard]] RigHand plan_rig_hand(const ToolPath& path, Hand hand,
                                    std::optional<std::size_t> first_tool, const Trocar& trocar,
                                    std::vector<TrocarMap> to_handle);

/// The path tool the handle holds at path time t_s (nullopt: an idle handle).
[[nodiscard]] std::optional<std::size_t> held_tool(const RigHand& hand, double t_s);
/// The handle's joints at path time t_s.
[[nodiscard]] JointState hand_joints(const ToolPath& path, const RigHand& hand, double t_s);
/// The handle's buttons at path time t_s: its instrument's row's (clutch, pedal), and the handle
/// button while it is pressed for an exchange.
[[nodiscard]] std::uint16_t hand_buttons(const ToolPath& path, const RigHand& hand, double t_s);

}  // namespace serosa::haptics
