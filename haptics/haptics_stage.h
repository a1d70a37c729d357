// The "haptics" effect: the 1 kHz haptic loop (haptics/haptic_loop.h) runs on its own thread
// beside the solver, driving one device for the (at most two) handles:
//  - script: a ScriptDevice plays the scene's scripted tool path in real time (headless
//    regression runs of the whole device path, without a rig);
//  - mouse: a MouseKeyboardDevice the trainee session's window feeds (feed_pointer());
//  - rig / rig-emulated: the libusb driver haptics::UsbRig (docs/rig-protocol.md) reads both
//    handles and receives the loop's force commands. "rig-emulated" is the same driver against
//    haptics::EmulatedRig (umockdev): with "rig-emulated:FILE" this stage creates the emulated
//    rig, whose handles play FILE (poses through the trocar kinematics into encoder counts,
//    jaw included) from the first step on, in wall-clock time but never more than a step ahead
//    of the simulation (EmulatedRig::follow); with plain "rig-emulated" someone else (a test)
//    created it before this stage. Either way the process runs under umockdev-wrapper. A rig that
//    is absent is not an error: the session runs, the handles' tools stay where they are with zero
//    force, a warning names the tools and the device, telemetry counts the "not_connected_ticks",
//    and a rig plugged in later is picked up without a restart (UsbRig's hotplug).
// Hand-offs (docs/ARCHITECTURE.md "Threads and hand-offs"), all through engine/seqlock.h:
//   loop -> solver: each handle's ToolState, written every tick; this stage (right after the
//     "tools" stage) takes the newest one at the step boundary and puts it into SimState::tools,
//     so the record stage records exactly what the solver consumed and a replay reproduces the
//     run bit for bit without the loop;
//   solver -> loop: a ContactModel published each step: step, time, each handle's simulated tip
//     and, with a contact stage, its local contact plane (the nearest organ surface point to the
//     tip from the collision BVH, SimState::events.contact_planes). The planes are the contact
//     stage's of the previous step (it runs after this stage): one solver step of latency.
//   window -> loop: the mouse device's cumulative PointerInput.
// Handles: the first two tools that are not endoscopes (scene order) take handles 0 and 1, except
// that a rig tool's `hand` picks its handle (left 0, right 1); they must share one device kind,
// and scripts one file. A rig handle's trocar is a mouse handle's (below). A
// scripted handle's trocar is its tool's `trocar` (its axis pointing at the tool's first scripted
// tip), or the first tip itself when none is given. A mouse handle's trocar is its tool's
// `trocar`, else 12 cm above the aim point (the organs' centroid; handle 1 5 cm to the side);
// its axis points at the aim point and the tool rests halfway there, or, given a rest tip
// (HapticsStageOptions::rest_pose: `serosa run` passes the first pose of the tool's script that
// the endoscope sees), at that tip, rolled to that pose's jaw plane.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <memory>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include <nlohmann/json.hpp>

#include "engine/math.h"
#include "engine/scene/scene.h"
#include "engine/sim_state.h"
#include "engine/stage.h"
#include "haptics/contact_model.h"
#include "haptics/hand_rack.h"
#include "haptics/mouse_device.h"

namespace serosa::haptics {
class Device;
class EmulatedRig;
class UsbRig;
class HapticLoop;
struct LoopStatus;
}  // namespace serosa::haptics

namespace serosa::haptics {

struct HapticsStageOptions {
  /// Ask for SCHED_FIFO and run the gap monitor (the trainee session); headless runs share the
  /// machine (CI) and leave both off.
  bool realtime = false;
  /// Where mouse handles' trocar axes point, m (compose passes the organs' centroid).
  Vec3 aim_m = Vec3::Zero();
  /// (tools, or empty) How a mouse-driven tool rests at the start: its trocar axis points at the
  /// pose's tip and the tip starts there, rolled to the pose's jaw plane. nullopt: halfway to
  /// aim_m, unrolled.
  std::vector<std::optional<ToolState>> rest_pose;
  /// Rig devices: how long the constructor waits for the rig to connect before it warns "rig not
  /// connected" and goes on, s.
  double rig_wait_s = 1.0;
};

class HapticsStage final : public Stage {
 public:
  /// Throws InputError when no tool can take a handle, the handles' device kinds differ, or the
  /// handle tools' scripts differ. The loop starts at the first step.
  explicit HapticsStage(const Scene& scene, const HapticsStageOptions& options = {});
  ~HapticsStage() override;

  [[nodiscard]] std::string_view name() const noexcept override { return "haptics"; }
  void step(const StepContext& ctx, SimState& state) override;

  /// Stops the loop (idempotent); telemetry is final afterwards.
  void stop();
  /// The loop's telemetry (LoopTelemetry::write_json) as JSON; stops the loop first.
  [[nodiscard]] nlohmann::json telemetry_json();
  /// The loop's live status (tick count, forces), readable from any thread while it runs.
  [[nodiscard]] haptics::LoopStatus status() const;
  /// Scene tool index of each handle (nullopt: idle handle).
  [[nodiscard]] const std::array<std::optional<std::size_t>, haptics::kHandles>& handle_tools()
      const noexcept {
    return m_tool;
  }
  /// The instruments the handles take in turn (null for scripted handles).
  [[nodiscard]] const haptics::HandRack* rack() const noexcept { return m_rack.get(); }
  /// The device kind driving the handles.
  [[nodiscard]] DeviceKind device_kind() const noexcept { return m_kind; }
  /// Mouse handles: the window's cumulative input (any one thread; no-op for a script device).
  void feed_pointer(const haptics::PointerInput& in) noexcept;
  /// Whether a rig drives the handles: its samples come in wall-clock time, so a run without a
  /// window must step at real time for the solver to see the hand's motion as it was made.
  [[nodiscard]] bool driven_by_rig() const noexcept;
  /// Whether a rig drives the handles and has been connected at some time in this run (so that
  /// its absence now is an unplug).
  [[nodiscard]] bool rig_was_connected() const noexcept;
  /// Whether the device is connected now (always true for script and mouse).
  [[nodiscard]] bool device_connected() const noexcept;
  /// The rig this stage emulates (device "rig-emulated:FILE"), else null: tests unplug it.
  [[nodiscard]] haptics::EmulatedRig* emulated_rig() noexcept { return m_emulated.get(); }
  /// The contact model published last (tests).
  [[nodiscard]] haptics::ContactModel last_model() const noexcept { return m_model.load(); }

 private:
  std::array<std::optional<std::size_t>, haptics::kHandles> m_tool{};
  DeviceKind m_kind = DeviceKind::kScript;
  haptics::ContactModelChannel m_model;
  // Declared before the device, so the driver (UsbRig) closes before the rig it talks to goes.
  std::unique_ptr<haptics::EmulatedRig> m_emulated;  // device "rig-emulated:FILE" only
  std::unique_ptr<haptics::Device> m_device;
  haptics::MouseKeyboardDevice* m_mouse = nullptr;  // m_device when it is the mouse
  haptics::UsbRig* m_rig = nullptr;                 // m_device when it is the rig
  bool m_reported_connected = false;                // rig state last logged (solver thread)
  std::string m_usb_error;  // why libusb could not start (then a never-connected stand-in)
  std::unique_ptr<haptics::HapticLoop> m_loop;
  bool m_started = false;
  std::uint32_t m_cut_events = 0;      // cuts seen so far (solver thread)
  std::uint32_t m_contact_events = 0;  // handles' touching-or-not changes so far
  std::array<bool, haptics::kHandles> m_touching{};
  // Each handle's instrument's jaw range (engine/jaw_range.h), rad: a rig handle is held to it.
  std::array<double, haptics::kHandles> m_jaw_max{};
  // Mouse and rig handles: the pose before the device's first sample (script handles: none).
  std::array<std::optional<ToolState>, haptics::kHandles> m_rest_pose{};
  // Mouse and rig: every instrument the handles take in turn (haptics/hand_rack.h); script
  // handles keep theirs (null).
  std::unique_ptr<haptics::HandRack> m_rack;
  std::vector<std::size_t> m_waiting;  // tools beyond the handles, waiting in their ports
  std::vector<ToolState> m_port;       // (rack instruments) each one's pose in its port
  std::array<bool, haptics::kHandles> m_pressed{};  // each handle button at the last step

  void build_rack(const Scene& scene, const HapticsStageOptions& options);
  void exchange(std::size_t h, SimState& state);
  void place_rack(SimState& state, std::size_t h, const ToolState& handle_pose);

  void emulate_rig(const Scene& scene, const std::filesystem::path& script,
                   const std::array<haptics::Trocar, haptics::kHandles>& trocars);
  void count_events(const SimState& state) noexcept;
  void wait_for_rig(double seconds);
  void warn_not_connected(const Scene& scene) const;
};

/// The trocar and rest joints of a mouse-driven handle (see the header comment): pivot at the
/// tool's trocar, else 12 cm above `aim` (handle 1: 5 cm to the side), axis towards `aim`,
/// resting halfway there; or, given `rest_tip`, axis towards it and the tip resting on it.
struct MouseHandle {
  haptics::Trocar trocar;
  haptics::JointState rest;
};
[[nodiscard]] MouseHandle mouse_handle(const Tool& tool, std::size_t handle, const Vec3& aim_m,
                                       const std::optional<ToolState>& rest_pose = std::nullopt);

/// The tissue's push on a tool's shaft (r.shaft_push_n, acting r.shaft_lever of the way from
/// the port to the tip) as the tip force with the same moment about the port: its lateral part
/// times the lever, its axial part unchanged (it passes through the port along the shaft), N.
[[nodiscard]] Vec3 shaft_push_at_tip(const ToolReaction& r, const ToolState& tool);

/// The trocar of a rig-driven handle: the same as a mouse handle's (mouse_handle().trocar).
[[nodiscard]] haptics::Trocar rig_trocar(const Tool& tool, std::size_t handle, const Vec3& aim_m);

}  // namespace serosa::haptics
