// What the trainee holds, for the session's overlay and picture: the instruments on the haptic
// handles (handle 0 the left hand, 1 the right), which one the mouse steers, how far each has its
// jaws open, whether its pedal is down and how far its tip is from the tissue.
#pragma once

#include <array>
#include <cstddef>
#include <optional>
#include <string>
#include <vector>

#include "engine/scene/scene.h"
#include "engine/sim_state.h"
#include "haptics/rig_protocol.h"
#include "render/render_frame.h"

namespace serosa::window {

/// Scene tool index of each haptic handle (nullopt: idle).
using HandleTools = std::array<std::optional<std::size_t>, haptics::kHandles>;

/// One OverlayHand per handle that holds a tool, from the consumed inputs (state.tools) and the
/// drawn tools' depth cue (frame.tools, filled by fill_render_tools).
[[nodiscard]] std::vector<render::OverlayHand> overlay_hands(const Scene& scene,
                                                             const SimState& state,
                                                             const HandleTools& handles,
                                                             std::size_t active_handle,
                                                             const render::RenderFrame& frame);

/// The instruments waiting in their ports (no handle holds them), by name, in scene order.
[[nodiscard]] std::vector<std::string> waiting_instruments(const Scene& scene,
                                                           const SimState& state,
                                                           const HandleTools& handles);

/// Marks the drawn tool of `tool` (a scene tool index) active, every other one not.
void mark_active_tool(render::RenderFrame& frame, std::optional<std::size_t> tool);

}  // namespace serosa::window
