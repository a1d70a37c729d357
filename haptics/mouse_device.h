// MouseKeyboardDevice: a trainee without the rig steers the instruments with mouse and keyboard.
// The window thread feeds cumulative input (a plain struct; no GLFW here) through a Seqlock; the
// loop turns what changed since its last poll into a goal for each handle and moves the handle
// towards it at the haptic rate:
//  - a drag moves the goal tip by move_m, in the scene frame: the window turns pixels into metres
//    along the picture's right and up at a fixed gain (window/pointer_control.h), so the tip goes
//    the way the pointer went whatever the instrument's insertion or shaft direction;
//  - the goal tip then goes through the trocar kinematics: the shaft pivots about its port and
//    the tip stays within max_cone_rad of the port's axis and between min and max insertion, so
//    a tip that cannot go where the drag asks goes as near as the port allows;
//  - depth steps (W/S, the wheel) insert or retract it along the shaft by m_per_step, roll steps
//    (Q/E) roll it by rad_per_step, and each press of Home (homes) brings it back to its rest
//    joints, in view (the rest pose serosa run gives each instrument);
//  - jaw_fraction (0 closed, 1 open) opens the jaws to that share of the instrument's range
//    (jaw_max_rad: engine/jaw_range.h), at most jaw_speed_rad_s fast;
//  - the joints follow the goal with time constant ease_s, so a frame's worth of motion that
//    arrives at once (the window reads its input once a frame) is spread over the loop's ticks
//    instead of jumping; ease_s = 0 follows at once.
//  - each press of X (exchanges) presses the handle button (kExchangeButton) until the handle is
//    reseated, at most kPressS: the haptics stage's exchange (haptics/hand_rack.h);
//  - after an exchange the haptics stage reseats the handle (reseat(), from the solver thread):
//    the handle is drawn back to its port and stays there until the stage has seen it drawn back
//    (admit()), however slow the solver's steps; then it inserts the new instrument towards its
//    rest joints at entry_speed_m_s along the port's axis. Drags then move through the rotation
//    that carries the scene's directions into the handle's own trocar frame.
// Cumulative values mean no motion is lost between polls.
#pragma once

#include <array>
#include <cstdint>

#include "engine/seqlock.h"
#include "haptics/device.h"

namespace serosa::haptics {

/// Cumulative input since the window opened, per handle (the window owns the accumulation);
/// jaw_fraction and buttons are the current state, not sums.
struct PointerInput {
  std::array<std::array<double, 3>, kHandles> move_m{};  ///< total drag, scene frame, m
  std::array<double, kHandles> depth_steps{};            ///< total insertion steps (+ = insert)
  std::array<double, kHandles> roll_steps{};             ///< total roll steps (+ = clockwise)
  std::array<double, kHandles> jaw_fraction{};           ///< jaws: 0 closed .. 1 fully open
  std::array<std::uint32_t, kHandles> buttons{};         ///< button bits (protocol layout)
  std::array<std::uint32_t, kHandles> homes{};           ///< times Home was pressed
  std::array<std::uint32_t, kHandles> exchanges{};       ///< times X was pressed
};

/// A handle's new instrument, from the solver thread (HapticsStage).
struct MouseSeat {
  std::array<std::uint32_t, kHandles> generation{};  ///< changes at each reseat of the handle
  std::array<std::uint32_t, kHandles> admitted{};    ///< the last generation the stage admitted
  std::array<JointState, kHandles> rest{};           ///< the instrument's rest joints
  std::array<double, kHandles> jaw_max_rad{1.0, 1.0};
  /// Scene directions -> the handle's trocar frame (w, x, y, z): the drag's rotation.
  std::array<std::array<double, 4>, kHandles> to_handle{
      {{1.0, 0.0, 0.0, 0.0}, {1.0, 0.0, 0.0, 0.0}}};
};

/// X holds the handle button down until the exchange it asks for has reseated the handle, or at
/// most this long, s: far longer than a solver step, so a step sees it however slow it is (a
/// sanitizer build on a busy machine included).
inline constexpr double kPressS = 2.0;

struct MouseMapping {
  double m_per_step = 0.003;      ///< insertion per depth step, m
  double rad_per_step = 0.1;      ///< roll per roll step, rad
  double max_cone_rad = 1.2;      ///< largest angle of the shaft from the port's axis, rad
  double min_insertion_m = 0.01;  ///< shortest insertion past the port, m
  double max_insertion_m = 0.3;   ///< longest, m
  double ease_s = 0.03;           ///< time constant of the joints following the goal, s (>= 0)
  double jaw_speed_rad_s = 4.0;   ///< fastest jaw motion, rad/s
  double entry_speed_m_s = 0.15;  ///< how fast a reseated handle inserts its instrument, m/s
  std::array<double, kHandles> jaw_max_rad{1.0, 1.0};  ///< each handle's instrument's range, rad
  std::array<JointState, kHandles> rest{};             ///< joints with no input (and after Home)
};

class MouseKeyboardDevice final : public Device {
 public:
  MouseKeyboardDevice(std::array<Trocar, kHandles> trocars, const MouseMapping& m = {});

  /// Window thread (single writer): the current cumulative input.
  void feed(const PointerInput& in) noexcept { m_input.store(in); }
  /// Solver thread (single writer): handle h's new instrument (see the header comment).
  void reseat(std::size_t h, const JointState& rest, double jaw_max_rad, const Quat& to_handle);
  /// Solver thread: the stage has seen handle h drawn back to its port since its last reseat,
  /// so the new instrument may go in.
  void admit(std::size_t h);

  bool poll(double now_s, DeviceSample& out) noexcept override;
  [[nodiscard]] bool connected() const noexcept override { return true; }
  void command(const DeviceCommand& c) noexcept override { m_last = c; }
  [[nodiscard]] const char* name() const noexcept override { return "mouse"; }
  [[nodiscard]] const DeviceCommand& last_command() const noexcept { return m_last; }

 private:
  void follow_input(std::size_t h, const PointerInput& in);
  void ease(std::size_t h, double dt_s, bool held);
  void take_seat(std::size_t h, const MouseSeat& seat);
  std::uint32_t press(std::size_t h, const PointerInput& in, double now_s);

  std::array<Trocar, kHandles> m_trocars;
  MouseMapping m_map;
  Seqlock<PointerInput> m_input{};
  Seqlock<MouseSeat> m_seat{};
  MouseSeat m_seat_out{};  // solver thread: the last seat stored
  // Loop thread only: the input last taken in, each handle's goal and joints, the last poll.
  PointerInput m_seen{};
  std::array<JointState, kHandles> m_goal{};
  std::array<JointState, kHandles> m_q{};
  std::array<std::uint32_t, kHandles> m_generation{};  // the seat each handle took
  std::array<bool, kHandles> m_entering{};             // inserting a new instrument
  std::array<Quat, kHandles> m_to_handle{Quat::Identity(), Quat::Identity()};
  std::array<double, kHandles> m_pressed_until{};  // the handle button's release, s
  double m_last_s = 0.0;
  std::uint64_t m_seq = 0;
  DeviceCommand m_last{};
};

/// The joints nearest `goal_tip_m` that the port allows: the shaft within max_cone_rad of the
/// port's axis, the insertion within [min_insertion_m, max_insertion_m]; roll and jaw of
/// `previous`.
[[nodiscard]] JointState reach(const Trocar& t, const Vec3& goal_tip_m, const JointState& previous,
                               const MouseMapping& m);

}  // namespace serosa::haptics
