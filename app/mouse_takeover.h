// MouseTakeover: the instructor (or trainee) takes over a paused replay with the mouse ("branch
// from replay"). After ReplayController::branch() the replay's tools follow a
// haptics::MouseKeyboardDevice instead of the recording:
//  - handles: the first two tools that are not endoscopes (scene order) take handles 0 and 1;
//  - each handle's trocar is put on its tool's shaft line through the pose at the branch (the
//    pivot at the tool's `trocar` distance from the tip, else 10 cm back along the shaft), its
//    frame the tool's orientation, so the device's rest joints (insertion only) reproduce that
//    pose exactly: taking over moves nothing until the input does;
//  - the jaws hold the opening the recording left them at (the input's jaw_fraction starts
//    there) until the input asks for another; then they move at the device's jaw speed (a jump
//    would cut or grab at once), over the instrument's range (engine/jaw_range.h).
// apply() polls the device with the cumulative input and hands the poses to the controller for
// its next step; it is deterministic (no thread), so a scripted input sequence stands in for the
// user in tests, and the branch recording holds exactly what the steps consumed.
#pragma once

#include <array>
#include <cstddef>
#include <memory>
#include <optional>
#include <vector>

#include "engine/scene.h"
#include "engine/tool_state.h"
#include "haptics/mouse_device.h"

namespace serosa::app {

class ReplayController;

class MouseTakeover {
 public:
  /// Takes the handles' poses from `tools` (the state at the branch, scene order).
  MouseTakeover(const Scene& scene, const std::vector<ToolState>& tools,
                const haptics::MouseMapping& mapping = {});

  /// Cumulative input at the branch: its jaw fractions hold the recorded jaws. Start
  /// accumulating from this.
  [[nodiscard]] const haptics::PointerInput& initial_input() const noexcept { return m_initial; }

  /// Feeds `in` (cumulative since the branch began, initial_input() included) to the device,
  /// polls it and sets the handles' tool inputs for the replay's next step (dt: the replay's).
  void apply(const haptics::PointerInput& in, ReplayController& replay);

  /// Scene tool index of each handle (nullopt: idle handle).
  [[nodiscard]] const std::array<std::optional<std::size_t>, haptics::kHandles>& handle_tools()
      const noexcept {
    return m_tool;
  }
  /// Each handle's trocar (tests check the rest pose).
  [[nodiscard]] const std::array<haptics::Trocar, haptics::kHandles>& trocars() const noexcept {
    return m_trocars;
  }

 private:
  std::array<std::optional<std::size_t>, haptics::kHandles> m_tool{};
  std::array<haptics::Trocar, haptics::kHandles> m_trocars{};
  haptics::MouseMapping m_map;
  std::unique_ptr<haptics::MouseKeyboardDevice> m_device;
  haptics::PointerInput m_initial{};
};

}  // namespace serosa::app
