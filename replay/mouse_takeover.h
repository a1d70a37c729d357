// MouseTakeover: the instructor (or trainee) takes over a paused replay with the mouse ("branch
// from replay"). After ReplayController::branch() the replay's instruments the mouse holds follow
// a haptics::MouseKeyboardDevice per hand instead of the recording, the way the trainee session
// hands them out (window/pointer_control.h: Tab makes the other hand active, X exchanges the active
// hand's instrument):
//  - at the branch, the left hand (handle 0) takes the instrument the recording's left hand held,
//    the right hand (handle 1) the right's (engine/instrument_hold.h; a hand that held none is
//    idle until X); a recording without hands (a script's) gives them its first two instruments
//    (scene order);
//  - X gives the active hand the next instrument of the scene (scene order after the one it
//    holds, wrapping, not the endoscope, not the one the other hand holds): any instrument the
//    recorded scene has can be taken over, the one the trainee got wrong included. The one it let
//    go of stays where the mouse left it, pedal released (no hand holds it); a tool the mouse
//    never took goes on as recorded (ReplayController);
//  - a hand's trocar is put on its instrument's shaft line through its pose when taken (the pivot
//    at the tool's `trocar` distance from the tip, else 10 cm back along the shaft), its frame
//    the tool's orientation, so the device's rest joints (insertion only) reproduce that pose
//    exactly: taking over moves nothing until the input does. An instrument X takes from its port
//    enters at once, just inside its trocar (the mapping's min_insertion_m), held by that hand;
//  - the jaws hold the opening the recording left them at until the input asks for another; then
//    they move at the device's jaw speed (a jump would cut or grab at once), over the
//    instrument's range (engine/jaw_range.h). The device's buttons (a hook's pedal) likewise keep
//    the recorded ones until the input toggles one;
//  - the endoscope (the scene's first, when the recording posed it) is the mouse's from the
//    branch on, through the session's scope control (window/scope_control.h: right button, I/K,
//    comma/period, O), from its pose at the branch: the instructor's view moves only when they
//    move it.
// poll() turns the cumulative input into the tool inputs for the replay's next step and apply()
// hands them to the controller; both are deterministic (no thread), so a scripted input sequence
// stands in for the user in tests, and the branch recording holds exactly what the steps consumed.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <memory>
#include <optional>
#include <vector>

#include "engine/scene/scene.h"
#include "engine/tool_state.h"
#include "haptics/mouse_device.h"
#include "window/scope_control.h"

namespace serosa::replay {

using window::ScopeControl;

class ReplayController;

/// One tool's input for the next step.
struct TakeoverInput {
  std::size_t tool = 0;  ///< scene tool index
  ToolState input;
};

class MouseTakeover {
 public:
  /// Takes the hands' instruments and the endoscope from `tools` (the state at the branch, scene
  /// order).
  MouseTakeover(const Scene& scene, const std::vector<ToolState>& tools,
                const haptics::MouseMapping& mapping = {});
  ~MouseTakeover();
  MouseTakeover(const MouseTakeover&) = delete;
  MouseTakeover& operator=(const MouseTakeover&) = delete;

  /// Cumulative input at the branch: its jaw fractions hold the recorded jaws. Start
  /// accumulating from this.
  [[nodiscard]] const haptics::PointerInput& initial_input() const noexcept { return m_initial; }

  /// Feeds `in` (cumulative since the branch began, initial_input() included) to the hands'
  /// devices, takes the instruments its new X presses ask for, and returns the inputs for the
  /// next step at time `t_s` after `step` steps: each hand's instrument, the endoscope, and once
  /// each instrument a hand let go of. `tools`: the inputs the last step consumed (scene order).
  [[nodiscard]] std::vector<TakeoverInput> poll(const haptics::PointerInput& in, double t_s,
                                                std::uint64_t step,
                                                const std::vector<ToolState>& tools);
  /// poll() at the replay's time and state, handed to the replay for its next step.
  void apply(const haptics::PointerInput& in, ReplayController& replay);

  /// Hand `h` takes instrument `tool` (scene index) from its pose in `tools` (the last step's
  /// inputs), letting go of the one it held; `in`: the cumulative input now (the new
  /// instrument's motion starts from it). Throws std::out_of_range for a bad hand or tool,
  /// std::invalid_argument for the endoscope or the other hand's instrument. X does this.
  void take(std::size_t h, std::size_t tool, const std::vector<ToolState>& tools,
            const haptics::PointerInput& in);

  /// Scene tool index of each hand's instrument (nullopt: an idle hand).
  [[nodiscard]] const std::array<std::optional<std::size_t>, haptics::kHandles>& handle_tools()
      const noexcept {
    return m_tool;
  }
  /// Each hand's trocar (tests check the rest pose).
  [[nodiscard]] const std::array<haptics::Trocar, haptics::kHandles>& trocars() const noexcept {
    return m_trocars;
  }
  /// The instruments a hand let go of, which stay where the mouse left them (scene order).
  [[nodiscard]] std::vector<std::size_t> left_tools() const;
  /// The endoscope the mouse drives (scene index), if any.
  [[nodiscard]] std::optional<std::size_t> scope_tool() const noexcept { return m_scope_tool; }
  /// Its control: the window feeds it its keys and right button (ScopeControl::update).
  [[nodiscard]] window::ScopeControl* scope() noexcept { return m_scope.get(); }

 private:
  /// What a hand's device saw of the input when its instrument was taken, and what it held.
  struct Seat {
    haptics::PointerInput base{};        // the cumulative input then
    double recorded_jaw_fraction = 0.0;  // the jaws as taken, of the device's range
    std::uint32_t recorded_buttons = 0;  // the instrument's buttons as taken (in-port cleared)
    bool jaw_held = true;                // the jaws still hold the recorded opening
  };
  void seat(std::size_t h, std::size_t tool, const ToolState& pose,
            const haptics::PointerInput& in);
  void let_go(std::size_t h, const std::vector<ToolState>& tools);
  [[nodiscard]] haptics::PointerInput device_input(std::size_t h, const haptics::PointerInput& in);
  void exchange_if_asked(const haptics::PointerInput& in, const std::vector<ToolState>& tools);
  [[nodiscard]] std::optional<std::size_t> next_instrument(std::size_t h) const;

  std::vector<Tool> m_tools;  // the scene's
  haptics::MouseMapping m_base_map;
  std::array<std::optional<std::size_t>, haptics::kHandles> m_tool{};
  std::array<haptics::Trocar, haptics::kHandles> m_trocars{};
  std::array<std::unique_ptr<haptics::MouseKeyboardDevice>, haptics::kHandles> m_device{};
  std::array<Seat, haptics::kHandles> m_seat{};
  std::array<std::uint32_t, haptics::kHandles> m_exchanges_seen{};
  std::vector<bool> m_left;             // (tools) let go of by a hand (and not taken again)
  std::vector<TakeoverInput> m_let_go;  // their last inputs, for the next poll
  bool m_hands = false;  // the recording says which hand holds what (engine/instrument_hold.h)
  std::optional<std::size_t> m_scope_tool;
  std::unique_ptr<window::ScopeControl> m_scope;
  haptics::PointerInput m_initial{};
};

}  // namespace serosa::replay
