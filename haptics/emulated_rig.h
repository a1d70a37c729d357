// EmulatedRig: the rig of docs/rig-protocol.md emulated in-process with umockdev, so that the
// unmodified libusb driver (UsbRig) runs against it with no hardware, udev, kernel module or root.
//
// umockdev's testbed provides the sysfs entry and the /dev/bus/usb node of a 1209:5E70 device; an
// ioctl handler answers usbdevfs (SUBMITURB, REAPURBNDELAY, DISCARDURB, CLEAR_HALT, ...). The
// emulated firmware produces one state packet per millisecond from a scripted tool path (poses ->
// trocar joints -> encoder counts; the path's buttons: clutch, pedal, handle button), decodes
// force packets strictly, keeps the 2 ms motor watchdog and measures the latency from each state
// packet it delivered to the force packet answering it.
// Faults can be injected: short packet, bad checksum, bad version, endpoint stall, unplug, replug.
//
// Requirements: the process runs with libumockdev-preload (umockdev-wrapper, or LD_PRELOAD) and
// the EmulatedRig is constructed before the libusb context (UsbRig) so libusb sees the testbed.
// ensure_umockdev_preload() re-executes a program under the preload.
#pragma once

#include <array>
#include <cstdint>
#include <memory>
#include <optional>
#include <vector>

#include "engine/scene/tool_path.h"
#include "haptics/rig_calibration.h"
#include "haptics/rig_hand_script.h"
#include "haptics/rig_protocol.h"

namespace serosa::haptics {

struct EmulatedRigConfig {
  ToolPath path;  ///< drives the handles (time 0 = construction; or follow())
  std::array<std::optional<std::size_t>, kHandles> tool_of_handle{};  ///< path tool per handle
  std::array<Trocar, kHandles> trocars{};
  /// Per handle, a scripted hand that exchanges instruments (haptics/rig_hand_script.h); where
  /// none is given the handle follows tool_of_handle's path through trocars[h] throughout.
  std::array<std::optional<RigHand>, kHandles> hands{};
  RigCalibration calibration{};
  double packet_period_s = 1e-3;  ///< state packet interval
  double watchdog_s = 2e-3;       ///< motors off when no valid force packet for this long
};

enum class RigFault : std::uint8_t {
  kShortPacket,  ///< next state packet truncated to 20 bytes
  kBadChecksum,  ///< next state packet with one flipped bit
  kBadVersion,   ///< next state packet with version 2 (valid checksum)
  kStall,        ///< IN endpoint halts until the host clears it
};

struct EmulatedRigStats {
  std::uint64_t packets_sent = 0;    ///< state packets delivered
  std::uint64_t forces_ok = 0;       ///< valid force packets received
  std::uint64_t forces_bad = 0;      ///< force packets rejected by decode_force
  std::uint64_t stalls_cleared = 0;  ///< CLEAR_HALT requests
  std::uint64_t watchdog_trips = 0;  ///< motor-on -> off transitions by the watchdog
  bool motors_on = false;            ///< firmware output enabled (watchdog fed and enable flag)
  ForcePacket last_force{};          ///< last valid force packet
  double last_force_time_s = 0.0;    ///< when it arrived (monotonic)
  /// (path tools) per handle: the largest pitch or yaw torque commanded (motors enabled) while
  /// that handle held that tool, N*m; the forces each instrument in turn sent to the hand
  std::vector<std::array<double, kHandles>> peak_torque_nm;
  /// (path tools) per handle: the same for the insertion force, N
  std::vector<std::array<double, kHandles>> peak_insertion_n;
};

class EmulatedRig {
 public:
  /// Creates the testbed and plugs the rig in. Throws std::runtime_error when the umockdev
  /// preload is not active or the testbed cannot be set up.
  explicit EmulatedRig(EmulatedRigConfig c);
  ~EmulatedRig();
  EmulatedRig(const EmulatedRig&) = delete;
  EmulatedRig& operator=(const EmulatedRig&) = delete;

  /// The handles follow a simulation that is at `sim_time_s` now and steps `step_s` at a time:
  /// from here the path plays on in wall-clock time, but never past sim_time_s + step_s. A
  /// simulation at real time sees the hand move as recorded; a slower one (a sanitizer build)
  /// sees the hand wait for it, so the procedure it plays stays the procedure. Called at every
  /// step (the path starts with the first). Never blocks (a seqlock, not the rig's mutex).
  void follow(double sim_time_s, double step_s);
  void unplug();
  void replug();
  [[nodiscard]] bool plugged() const;
  /// Queues a fault for the next state packet(s).
  void inject(RigFault f);

  /// Statistics; motors_on is evaluated at the time of the call (watchdog applied).
  [[nodiscard]] EmulatedRigStats stats() const;
  /// Latencies from a state packet's delivery to the arrival of the force packet answering it, s
  /// (the first answer to each state packet only).
  [[nodiscard]] std::vector<double> latencies() const;
  /// What it was built with (its hands completed: one per handle).
  [[nodiscard]] const EmulatedRigConfig& config() const;
  /// Joints the firmware reports for handle h at path time t (for checks).
  [[nodiscard]] JointState joints_at(std::size_t h, double t_s) const;

 private:
  struct Impl;
  std::unique_ptr<Impl> m;
};

/// True when libumockdev-preload is loaded into this process.
[[nodiscard]] bool umockdev_preload_active();

/// If the preload is not active, re-executes argv under `umockdev-wrapper` (adding
/// verify_asan_link_order=0 to ASAN_OPTIONS) and never returns; returns when it is active.
/// Throws std::runtime_error when the re-exec fails.
void ensure_umockdev_preload(char** argv);

}  // namespace serosa::haptics
