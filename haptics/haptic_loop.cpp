#include "haptics/haptic_loop.h"

#include <spdlog/spdlog.h>
#include <time.h>

#include <algorithm>
#include <cmath>

namespace serosa::haptics {
namespace {

constexpr double kEventWindowS = 20e-3;  // force steps are tracked this long after an event

void cpu_relax() noexcept {
#if defined(__x86_64__) || defined(__i386__)
  __builtin_ia32_pause();
#endif
}

GapMonitorConfig monitor_config(const HapticLoopConfig& c) {
  GapMonitorConfig m = c.monitor;
  if (m.cpu < 0) m.cpu = c.cpu;  // watch the loop's own core: a paused vCPU stalls both
  return m;
}

double clamp_abs(double v, double limit) { return std::clamp(v, -limit, limit); }

bool finite(const JointEffort& e) {
  return std::isfinite(e.pitch_Nm) && std::isfinite(e.yaw_Nm) && std::isfinite(e.roll_Nm) &&
         std::isfinite(e.insertion_N) && std::isfinite(e.jaw_Nm);
}

}  // namespace

HapticLoop::HapticLoop(Device& device, const ContactModelChannel& model, const HapticLoopConfig& c)
    : m_device(device),
      m_model(model),
      m_c(c),
      m_renderer(c.force),
      m_monitor(monitor_config(c)),
      m_tel(std::make_unique<LoopTelemetry>()) {
  m_tel->period_s = c.period_s;
  ForceRendererParams force = c.force;
  force.max_stiffness_Npm =
      std::min(force.max_stiffness_Npm,
               kPassivityMargin * passivity_bound_Npm(c.device_damping_Nspm, c.period_s));
  m_renderer = ForceRenderer(force);
}

HapticLoop::~HapticLoop() { stop(); }

void HapticLoop::start() {
  if (m_thread.joinable()) return;
  m_stop.store(false);
  if (m_c.gap_monitor) m_monitor.start();
  m_thread = std::thread([this] { run(); });
}

void HapticLoop::stop() {
  m_stop.store(true);
  if (m_thread.joinable()) m_thread.join();
  m_monitor.stop();
  classify_pending(0, true);
  m_tel->monitor_gaps = m_monitor.gaps();
}

void HapticLoop::classify_pending(std::int64_t now_ns, bool all) noexcept {
  const auto period_ns = static_cast<std::int64_t>(std::llround(m_c.period_s * 1e9));
  std::size_t kept = 0;
  for (std::size_t i = 0; i < m_n_pending; ++i) {
    const LateInterval& l = m_pending[i];
    if (!all && now_ns - l.to_ns < 2 * period_ns) {
      m_pending[kept++] = l;
      continue;
    }
    // A platform stall that made the loop late by `late` froze the monitor for at least
    // late + spin (the monitor, below the loop on the same core, is blocked during the spin
    // anyway); the loop's ordinary spin alone blocks it for only about spin.
    const std::int64_t late = l.to_ns - l.from_ns - period_ns;
    const auto spin_ns = static_cast<std::int64_t>(m_c.spin_s * 1e9);
    if (m_monitor.saw_gap(l.from_ns, l.to_ns, late + spin_ns * 3 / 4)) {
      ++m_tel->platform_stalls;  // the monitor thread did not run either
    } else {
      ++m_tel->sched_delays;
      m_tel->record_clean(l.to_ns - l.from_ns);
      if (l.has_next) m_tel->record_clean(l.next_ns);
    }
  }
  m_n_pending = kept;
}

void HapticLoop::send_zero() noexcept {
  DeviceCommand cmd;
  cmd.tick = m_ticks;
  cmd.state_sequence = m_sample.sequence;
  cmd.enable = false;
  m_device.command(cmd);
}

void HapticLoop::run() {
  // Set-up, before the periodic part: scheduling, pinning, one log line each.
  const bool rt = m_c.realtime && try_realtime(m_c.priority);
  const bool pinned = m_c.cpu >= 0 && pin_to_cpu(m_c.cpu);
  m_tel->realtime = rt;
  m_tel->cpu = pinned ? m_c.cpu : -1;
  if (m_c.realtime && !rt) {
    spdlog::warn("haptics: SCHED_FIFO refused; the 1 kHz loop runs at normal priority");
  } else if (rt) {
    spdlog::info("haptics: 1 kHz loop on SCHED_FIFO priority {}", m_c.priority);
  }
  if (m_c.cpu >= 0 && !pinned) spdlog::warn("haptics: could not pin the loop to core {}", m_c.cpu);

  const auto period = static_cast<std::int64_t>(std::llround(m_c.period_s * 1e9));
  const auto spin = static_cast<std::int64_t>(std::llround(m_c.spin_s * 1e9));
  std::int64_t next = monotonic_ns() + period;
  while (!m_stop.load(std::memory_order_relaxed)) {
    // Sleep to just before the deadline, then spin to it.
    const std::int64_t wake = next - spin;
    timespec ts{static_cast<time_t>(wake / 1'000'000'000), static_cast<long>(wake % 1'000'000'000)};
    while (clock_nanosleep(CLOCK_MONOTONIC, TIMER_ABSTIME, &ts, nullptr) == EINTR) {
    }
    std::int64_t now = monotonic_ns();
    while (now < next) {
      cpu_relax();
      now = monotonic_ns();
    }
    tick(now);
    next += period;
    // Late past the next deadline: skip the missed ones (no replay), resume one period on.
    const std::int64_t after = monotonic_ns();
    if (after > next) {
      const std::int64_t missed = (after - next) / period + 1;
      m_tel->missed_deadlines += static_cast<std::uint64_t>(missed);
      next += missed * period;
    }
  }
  send_zero();
}

// One tick, in its stages: timing, device sample, model, safety gates and force, force steps
// after events, out.
void HapticLoop::tick(std::int64_t now_ns) noexcept {
  const std::int64_t work_start_ns = monotonic_ns();
  const double now = static_cast<double>(now_ns) * 1e-9;
  double dt = m_c.period_s;
  const bool gap = record_timing(now_ns, dt);
  poll_device(now);
  take_model(now);
  DeviceCommand cmd;
  std::array<Vec3, kHandles> force{Vec3::Zero(), Vec3::Zero()};
  const ZeroReason zero = render_force(now, dt, gap, cmd, force);
  record_event_steps(now, zero, force, cmd);
  m_prev_force = force;
  for (std::size_t h = 0; h < kHandles; ++h) m_prev_jaw_Nm[h] = cmd.effort[h].jaw_Nm;
  send(now, cmd, zero, force);
  m_last_work_ns = monotonic_ns() - work_start_ns;
  m_tel->max_tick_work_ns =
      std::max(m_tel->max_tick_work_ns, static_cast<std::uint64_t>(m_last_work_ns));
}

// Period, late ticks (platform stall or own overrun), gaps past the watchdog; dt: this tick's
// period, s. Returns whether the tick comes after a gap.
bool HapticLoop::record_timing(std::int64_t now_ns, double& dt) noexcept {
  LoopTelemetry& tel = *m_tel;
  const auto period_ns = static_cast<std::int64_t>(std::llround(m_c.period_s * 1e9));
  bool gap = false;
  if (m_ticks > 0) {
    const std::int64_t p = now_ns - m_last_tick_ns;
    tel.record_period(p);
    bool held = false;  // held back from the stall-free histogram until classified
    dt = static_cast<double>(p) * 1e-9;
    const auto late_ns = static_cast<std::int64_t>(m_c.late_threshold_s * 1e9);
    if (p > period_ns + late_ns) {
      ++tel.late_ticks;
      if (m_last_work_ns > period_ns / 2) {
        ++tel.loop_overruns;  // the previous tick itself took too long
      } else if (m_n_pending < m_pending.size()) {
        // Classified a little later: a monitor on this core records its gap only once the loop
        // lets it run again.
        m_pending[m_n_pending++] = {m_last_tick_ns, now_ns, 0, false};
        held = true;
      } else {
        ++tel.sched_delays;  // more late ticks at once than slots: counted unexplained
      }
    } else if (m_n_pending > 0 && m_pending[m_n_pending - 1].to_ns == m_last_tick_ns) {
      m_pending[m_n_pending - 1].next_ns = p;
      m_pending[m_n_pending - 1].has_next = true;
      held = true;
    }
    if (!held) tel.record_clean(p);
    if (dt > m_c.watchdog_s) {
      gap = true;
      ++tel.gaps;
    }
  }
  classify_pending(now_ns, false);
  m_last_tick_ns = now_ns;
  ++m_ticks;
  tel.ticks = m_ticks;
  return gap;
}

// The newest device sample.
void HapticLoop::poll_device(double now) noexcept {
  DeviceSample s;
  if (m_device.poll(now, s)) {
    m_sample = s;
    m_have_sample = true;
    m_sample_time_s = now;
    for (std::size_t h = 0; h < kHandles; ++h)
      m_friction[h].sample(s.joints[h].insertion_m, now, m_c.trocar_friction);
    ++m_tel->device_samples;
  }
}

// The newest model (only copied when the solver published a new one), and a force event when its
// cut or contact counters moved.
void HapticLoop::take_model(double now) noexcept {
  LoopTelemetry& tel = *m_tel;
  const std::uint64_t version = m_model.version();
  if (version == m_model_version) return;
  ContactModel m;
  if (!m_model.try_load(m)) return;
  m_model_version = version;
  if (m.step == 0 || m.step == m_model_step) return;
  m_model_step = m.step;
  m_model_time_s = now;
  m_renderer.set_model(m, now);
  ++tel.models;
  if (m_events_seen && (m.cut_events != m_cut_events || m.contact_events != m_contact_events)) {
    ForceEvent& e = tel.events[tel.n_events % LoopTelemetry::kEvents];
    e.time_s = now;
    e.sim_time_s = m.time_s;
    e.kind =
        (m.cut_events != m_cut_events ? 1u : 0u) | (m.contact_events != m_contact_events ? 2u : 0u);
    e.max_step_N = 0.0;
    e.max_jaw_step_Nm = 0.0;
    ++tel.n_events;
    m_event_until_s = now + kEventWindowS;
  }
  m_events_seen = true;
  m_cut_events = m.cut_events;
  m_contact_events = m.contact_events;
}

// Why the force must be zero this tick (kNone: it may be rendered).
ZeroReason HapticLoop::safety_gate(double now, bool gap) const noexcept {
  if (gap) return ZeroReason::kGap;
  if (!m_device.connected()) return ZeroReason::kUnplugged;
  if (!m_have_sample || now - m_sample_time_s > m_c.device_timeout_s)
    return ZeroReason::kDeviceStale;
  if (!m_renderer.has_model() || now - m_model_time_s > m_c.model_timeout_s)
    return ZeroReason::kNoModel;
  return ZeroReason::kNone;
}

// The safety gates, then each handle's force and joint efforts into `cmd` (zeroed when a gate or
// a non-finite value says so). Returns the zero reason.
ZeroReason HapticLoop::render_force(double now, double dt, bool gap, DeviceCommand& cmd,
                                    std::array<Vec3, kHandles>& force) noexcept {
  LoopTelemetry& tel = *m_tel;
  ZeroReason zero = safety_gate(now, gap);
  cmd.tick = m_ticks;
  cmd.state_sequence = m_sample.sequence;
  if (zero == ZeroReason::kNone) {
    const double max_step = m_c.force.slew_N_per_s * std::clamp(dt, 0.0, 2e-3);
    for (std::size_t h = 0; h < kHandles && zero == ZeroReason::kNone; ++h) {
      const auto& tip = m_sample.pose[h].tip_m;
      const Vec3 proxy(tip[0], tip[1], tip[2]);
      Vec3 f;
      if (!m_renderer.render(h, proxy, now, dt, f)) {
        zero = ZeroReason::kNotFinite;
        break;
      }
      if ((f - m_prev_force[h]).norm() >= max_step * (1.0 - 1e-9) && max_step > 0.0) {
        ++tel.slew_limited_ticks;
      }
      double jaw = 0.0;
      if (!m_renderer.jaw_torque(h, now, dt, jaw)) {
        zero = ZeroReason::kNotFinite;
        break;
      }
      JointEffort e = tip_to_joint(m_c.trocars[h], m_sample.joints[h], f, Vec3::Zero(), jaw);
      e.insertion_N +=
          m_friction[h].force_N(m_c.trocar_friction);  // the port's drag, along the shaft
      e.pitch_Nm = clamp_abs(e.pitch_Nm, m_c.max_joint_torque_Nm);
      e.yaw_Nm = clamp_abs(e.yaw_Nm, m_c.max_joint_torque_Nm);
      e.roll_Nm = clamp_abs(e.roll_Nm, m_c.max_roll_torque_Nm);
      e.insertion_N = clamp_abs(e.insertion_N, m_c.force.rated_force_N);
      e.jaw_Nm = clamp_abs(e.jaw_Nm, m_c.max_jaw_torque_Nm);
      if (!finite(e)) {
        zero = ZeroReason::kNotFinite;
        break;
      }
      cmd.effort[h] = e;
      cmd.tip_force_N[h] = f;
      force[h] = f;
    }
  }
  if (zero != ZeroReason::kNone) {
    cmd.enable = false;
    cmd.effort = {};
    cmd.tip_force_N = {Vec3::Zero(), Vec3::Zero()};
    force = {Vec3::Zero(), Vec3::Zero()};
    m_renderer.reset();  // the model stays; the force ramps back from zero afterwards
    for (TrocarFriction& fr : m_friction) fr.reset();
    ++tel.zero_ticks[static_cast<std::size_t>(zero)];
  } else {
    cmd.enable = true;
  }
  return zero;
}

// Force steps after contact and cut events.
// A safety stop (a gap, a stale device: zero_ticks counts them) drops the force at once by
// design; the steps measured here are the rendered ones, which the slew limits bound (the ramp
// back from zero after a stop is one of them).
void HapticLoop::record_event_steps(double now, ZeroReason zero,
                                    const std::array<Vec3, kHandles>& force,
                                    const DeviceCommand& cmd) noexcept {
  LoopTelemetry& tel = *m_tel;
  if (now > m_event_until_s || tel.n_events == 0 || zero != ZeroReason::kNone) return;
  ForceEvent& e = tel.events[(tel.n_events - 1) % LoopTelemetry::kEvents];
  for (std::size_t h = 0; h < kHandles; ++h) {
    e.max_step_N = std::max(e.max_step_N, (force[h] - m_prev_force[h]).norm());
    e.max_jaw_step_Nm =
        std::max(e.max_jaw_step_Nm, std::abs(cmd.effort[h].jaw_Nm - m_prev_jaw_Nm[h]));
  }
}

// Out: the device command, the tool states for the solver, the live status.
void HapticLoop::send(double now, const DeviceCommand& cmd, ZeroReason zero,
                      const std::array<Vec3, kHandles>& force) noexcept {
  m_device.command(cmd);
  if (m_have_sample) {
    for (std::size_t h = 0; h < kHandles; ++h) {
      ToolState t = m_sample.pose[h];
      t.tick = m_ticks;
      t.time_s = now;
      t.buttons = m_sample.buttons[h];
      m_tools[h].store(t);
    }
  }
  LoopStatus st;
  st.tick = m_ticks;
  st.time_s = now;
  st.zero_reason = static_cast<std::uint32_t>(zero);
  st.enabled = cmd.enable ? 1u : 0u;
  for (std::size_t h = 0; h < kHandles; ++h) {
    st.tip_force_N[h] = {force[h].x(), force[h].y(), force[h].z()};
  }
  st.device_sequence = m_sample.sequence;
  m_status.store(st);
  ++m_command_seq;
}

}  // namespace serosa::haptics
