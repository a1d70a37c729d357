// Device: the one interface every haptic input sits behind (USB rig, emulated rig, mouse and
// keyboard, scripted tool path, replay). The 1 kHz loop calls poll() and command() once per tick;
// implementations must not block, allocate, log or take a lock the solver holds there.
#pragma once

#include <array>
#include <cstdint>
#include <type_traits>

#include "engine/tool_state.h"
#include "haptics/rig_protocol.h"
#include "haptics/trocar_kinematics.h"

namespace serosa::haptics {

/// One device reading, copied out whole (trivially copyable: crosses threads through a Seqlock).
struct DeviceSample {
  std::uint64_t sequence = 0;  ///< device packet sequence (or sample index for software devices)
  double time_s = 0.0;         ///< host monotonic time the sample was taken or received, s
  std::array<JointState, kHandles> joints{};      ///< per handle, trocar joint space
  std::array<ToolState, kHandles> pose{};         ///< per handle, tool pose in the scene frame
  std::array<std::uint32_t, kHandles> buttons{};  ///< per handle, button bits (protocol layout)
  std::uint32_t status = 0;                       ///< device status bits (StatusBits), 0 if none
};
static_assert(std::is_trivially_copyable_v<DeviceSample>);

/// What the loop asks the device to render in one tick.
struct DeviceCommand {
  std::uint64_t tick = 0;            ///< loop tick that computed it
  std::uint64_t state_sequence = 0;  ///< DeviceSample::sequence it answers (latency tracing)
  bool enable = false;               ///< false: motors off (all efforts zero)
  std::array<JointEffort, kHandles> effort{};  ///< per handle joint efforts (already clamped)
  std::array<Vec3, kHandles> tip_force_N{Vec3::Zero(), Vec3::Zero()};  ///< rendered tip force
};

class Device {
 public:
  Device() = default;
  Device(const Device&) = delete;
  Device& operator=(const Device&) = delete;
  virtual ~Device() = default;

  /// Newest reading since the last call, at loop time now_s (CLOCK_MONOTONIC seconds). Returns
  /// false (out untouched) when nothing new arrived.
  virtual bool poll(double now_s, DeviceSample& out) noexcept = 0;
  /// False while the device is unplugged or not yet opened: the loop renders zero force.
  [[nodiscard]] virtual bool connected() const noexcept = 0;
  /// Sends one force command. Never blocks; a command that cannot be sent is dropped (counted
  /// by the implementation).
  virtual void command(const DeviceCommand& c) noexcept = 0;
  /// Short name for logs and reports ("usb-rig", "script", ...).
  [[nodiscard]] virtual const char* name() const noexcept = 0;
};

/// Monotonic clock in seconds (CLOCK_MONOTONIC), the time base of every haptics timestamp.
[[nodiscard]] double monotonic_s() noexcept;

}  // namespace serosa::haptics
