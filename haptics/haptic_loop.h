// HapticLoop: the 1 kHz haptic servo thread.
//
// Each tick (paced by absolute deadlines: clock_nanosleep(TIMER_ABSTIME) to spin_s before the
// deadline, then a short spin) the loop
//   1. reads the newest DeviceSample (never an old one: after a gap it resumes from fresh state),
//   2. takes the newest ContactModel the solver published (Seqlock, lock-free, never waits),
//   3. renders the tip force per handle (ForceRenderer: coupling + local contacts, blended between
//      models, clamped to the rated maximum, slew limited) and maps it to joint efforts through
//      the trocar kinematics (clamped again per joint),
//   4. sends the command to the device and publishes each handle's ToolState (Seqlock) for the
//      solver.
// Safety: zero force (motors disabled) on the tick that sees an unplugged device, a device sample
// older than device_timeout_s, no model (or one older than model_timeout_s), a NaN anywhere, or a
// period longer than watchdog_s (a stalled loop; the rig firmware's own 2 ms watchdog covers the
// stall itself, docs/rig-protocol.md). After any safety zero the force ramps back from zero at
// the slew limit. Deadlines that passed during a stall are counted and skipped, not replayed.
// Inside the loop: no allocation, no logging, no lock shared with the solver.
#pragma once

#include <array>
#include <atomic>
#include <cstdint>
#include <memory>
#include <thread>

#include "engine/seqlock.h"
#include "engine/tool_state.h"
#include "haptics/contact_model.h"
#include "haptics/device.h"
#include "haptics/force_renderer.h"
#include "haptics/gap_monitor.h"
#include "haptics/loop_telemetry.h"
#include "haptics/trocar_friction.h"
#include "haptics/trocar_kinematics.h"

namespace serosa::haptics {

struct HapticLoopConfig {
  double period_s = 1e-3;             ///< tick period, s
  double spin_s = 200e-6;             ///< spin before each deadline, s
  bool realtime = true;               ///< ask for SCHED_FIFO (logged fallback when refused)
  int priority = 80;                  ///< SCHED_FIFO priority
  int cpu = -1;                       ///< pin the loop to this core (-1: no pinning)
  double watchdog_s = 2e-3;           ///< a period longer than this is a gap: zero force, reset
  double late_threshold_s = 0.25e-3;  ///< period beyond period_s + this is a late tick
  double device_timeout_s = 2e-3;     ///< no fresh device sample for this long: zero force
  double model_timeout_s = 0.25;      ///< newest model older than this (loop time): zero force
  double max_joint_torque_Nm = 1.5;   ///< pitch/yaw torque limit (rated), N*m
  double max_roll_torque_Nm = 0.1;    ///< roll torque limit, N*m
  double max_jaw_torque_Nm = 0.2;     ///< jaw torque limit, N*m
  std::array<Trocar, kHandles> trocars{};  ///< per handle port geometry
  ForceRendererParams force{};             ///< includes rated_force_N and the slew limit
  TrocarFrictionParams trocar_friction{};  ///< the ports' drag on the insertion axis
  /// The device's own damping at the tool tip, N s/m. A sampled virtual wall of stiffness K is
  /// passive while K < 2 b / T (Colgate and Schenkel 1997; T the period): the renderer's total
  /// stiffness is capped at kPassivityMargin of that (ForceRendererParams::max_stiffness_Npm,
  /// unless set lower). The default is the device model `serosa bench haptics` measures the
  /// bound on (handle and hand, 2 N s/m: its energy decay crosses zero at 2 b / T = 4000 N/m,
  /// docs/BENCHMARKS.md "Coupling stiffness"), so a cap of 3200 N/m; identify it on each rig.
  double device_damping_Nspm = 2.0;
  bool gap_monitor = true;     ///< run a GapMonitor to classify late ticks
  GapMonitorConfig monitor{};  ///< by default it polls every 100 us on the loop's own core
                               ///< (cpu = -1 here: follow HapticLoopConfig::cpu)
};

/// Live summary, published every tick (Seqlock).
struct LoopStatus {
  std::uint64_t tick = 0;
  double time_s = 0.0;
  std::uint32_t zero_reason = 0;  ///< ZeroReason of the last tick
  std::uint32_t enabled = 0;      ///< motors enabled in the last command
  std::array<std::array<double, 3>, kHandles> tip_force_N{};  ///< last rendered tip forces
  std::uint64_t device_sequence = 0;  ///< sequence of the device sample last used
};

class HapticLoop {
 public:
  /// The loop reads `model` (written by the solver) and drives `device`; both must outlive it.
  HapticLoop(Device& device, const ContactModelChannel& model, const HapticLoopConfig& c = {});
  HapticLoop(const HapticLoop&) = delete;
  HapticLoop& operator=(const HapticLoop&) = delete;
  ~HapticLoop();

  /// Starts the thread (and the gap monitor). Logs once whether SCHED_FIFO and pinning held.
  void start();
  /// Stops the thread; the device's last command is motors off. Late ticks still awaiting
  /// classification are classified here.
  void stop();
  [[nodiscard]] bool running() const noexcept { return m_thread.joinable(); }

  /// One tick at CLOCK_MONOTONIC time now_ns. The thread calls it; tests may call it directly
  /// with synthetic times while the thread is not running.
  void tick(std::int64_t now_ns) noexcept;

  /// Per handle tool state for the solver (written every tick with a fresh device sample).
  [[nodiscard]] const Seqlock<ToolState>& tool_state(std::size_t handle) const noexcept {
    return m_tools[handle];
  }
  [[nodiscard]] const Seqlock<LoopStatus>& status() const noexcept { return m_status; }
  /// Telemetry; read it while the thread is stopped.
  [[nodiscard]] const LoopTelemetry& telemetry() const noexcept { return *m_tel; }
  [[nodiscard]] const HapticLoopConfig& config() const noexcept { return m_c; }
  /// The gap monitor (tests inject gaps through it).
  [[nodiscard]] GapMonitor& gap_monitor() noexcept { return m_monitor; }

 private:
  void run();
  void send_zero() noexcept;
  void classify_pending(std::int64_t now_ns, bool all) noexcept;
  // The stages of tick(), in order (haptic_loop.cpp).
  bool record_timing(std::int64_t now_ns, double& dt) noexcept;
  void poll_device(double now) noexcept;
  void take_model(double now) noexcept;
  [[nodiscard]] ZeroReason safety_gate(double now, bool gap) const noexcept;
  ZeroReason render_force(double now, double dt, bool gap, DeviceCommand& cmd,
                          std::array<Vec3, kHandles>& force) noexcept;
  void record_event_steps(double now, ZeroReason zero, const std::array<Vec3, kHandles>& force,
                          const DeviceCommand& cmd) noexcept;
  void send(double now, const DeviceCommand& cmd, ZeroReason zero,
            const std::array<Vec3, kHandles>& force) noexcept;

  Device& m_device;
  const ContactModelChannel& m_model;
  HapticLoopConfig m_c;
  ForceRenderer m_renderer;
  GapMonitor m_monitor;
  std::unique_ptr<LoopTelemetry> m_tel;  // large: on the heap, allocated once
  std::array<Seqlock<ToolState>, kHandles> m_tools{};
  Seqlock<LoopStatus> m_status{};
  std::thread m_thread;
  std::atomic<bool> m_stop{false};

  // Loop-thread state.
  std::int64_t m_last_tick_ns = 0;
  std::uint64_t m_ticks = 0;
  DeviceSample m_sample{};
  bool m_have_sample = false;
  double m_sample_time_s = 0.0;
  std::uint64_t m_model_version = 0;
  std::uint64_t m_model_step = 0;
  double m_model_time_s = 0.0;
  std::uint32_t m_cut_events = 0;
  std::uint32_t m_contact_events = 0;
  bool m_events_seen = false;
  double m_event_until_s = -1.0;
  std::array<Vec3, kHandles> m_prev_force{Vec3::Zero(), Vec3::Zero()};
  std::array<double, kHandles> m_prev_jaw_Nm{};
  std::array<TrocarFriction, kHandles> m_friction{};
  std::uint64_t m_command_seq = 0;
  std::int64_t m_last_work_ns = 0;  // time spent inside the previous tick
  struct LateInterval {
    std::int64_t from_ns = 0;
    std::int64_t to_ns = 0;
    std::int64_t next_ns = 0;  // the period after it (short when deadlines catch up)
    bool has_next = false;
  };
  std::array<LateInterval, 16> m_pending{};  // late ticks awaiting classification
  std::size_t m_n_pending = 0;
};

}  // namespace serosa::haptics
