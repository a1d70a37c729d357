// MouseKeyboardDevice: a trainee without the rig steers the instruments with mouse and keyboard.
// The window thread feeds cumulative input (a plain struct; no GLFW here) through a Seqlock; the
// loop maps it to joints about each trocar:
//   yaw   = rest.yaw   + dx_px * rad_per_px        pitch = rest.pitch + dy_px * rad_per_px
//   insertion = rest.insertion + scroll_steps * m_per_step  (clamped to [0, max_insertion_m])
//   roll  = rest.roll  + roll_steps * rad_per_step  jaw = jaw_open ? jaw_open_rad : 0
// pitch is clamped to +-max_pitch_rad. Cumulative values mean no motion is lost between polls.
#pragma once

#include <array>
#include <cstdint>

#include "engine/seqlock.h"
#include "haptics/device.h"

namespace serosa::haptics {

/// Cumulative input since the window opened, per handle (the window owns the accumulation).
struct PointerInput {
  std::array<double, kHandles> dx_px{};            ///< total horizontal pointer motion, px
  std::array<double, kHandles> dy_px{};            ///< total vertical pointer motion, px
  std::array<double, kHandles> scroll_steps{};     ///< total scroll, wheel steps (+ = insert)
  std::array<double, kHandles> roll_steps{};       ///< total roll key presses (+ = clockwise)
  std::array<std::uint32_t, kHandles> jaw_open{};  ///< 1 while the jaw key is held
  std::array<std::uint32_t, kHandles> buttons{};   ///< button bits (protocol layout)
};

struct MouseMapping {
  double rad_per_px = 0.002;
  double m_per_step = 0.005;
  double rad_per_step = 0.1;
  double jaw_open_rad = 0.6;
  double max_pitch_rad = 1.2;
  double max_insertion_m = 0.3;
  std::array<JointState, kHandles> rest{};  ///< joints with no input
};

class MouseKeyboardDevice final : public Device {
 public:
  MouseKeyboardDevice(std::array<Trocar, kHandles> trocars, const MouseMapping& m = {})
      : m_trocars(trocars), m_map(m) {}

  /// Window thread (single writer): the current cumulative input.
  void feed(const PointerInput& in) noexcept { m_input.store(in); }

  bool poll(double now_s, DeviceSample& out) noexcept override;
  [[nodiscard]] bool connected() const noexcept override { return true; }
  void command(const DeviceCommand& c) noexcept override { m_last = c; }
  [[nodiscard]] const char* name() const noexcept override { return "mouse"; }
  [[nodiscard]] const DeviceCommand& last_command() const noexcept { return m_last; }

 private:
  std::array<Trocar, kHandles> m_trocars;
  MouseMapping m_map;
  Seqlock<PointerInput> m_input{};
  std::uint64_t m_seq = 0;
  DeviceCommand m_last{};
};

}  // namespace serosa::haptics
