// LoopTelemetry: what the 1 kHz loop counts about itself, preallocated so that recording never
// allocates. Written only by the loop thread; read it after HapticLoop::stop() (or copy it from a
// stopped loop). write_json() produces the "haptics" object of the session report.
#pragma once

#include <array>
#include <cstdint>
#include <ostream>

namespace serosa::haptics {

/// Why a tick rendered zero force (index into LoopTelemetry::zero_ticks).
enum class ZeroReason : std::uint8_t {
  kNone = 0,
  kUnplugged,    ///< device not connected
  kDeviceStale,  ///< no fresh device sample within device_timeout_s
  kNoModel,      ///< no ContactModel published yet, or it is older than model_timeout_s
  kNotFinite,    ///< NaN or infinity in the model, the proxy or the force
  kGap,          ///< first tick after a loop gap longer than the watchdog
  kCount
};

/// A contact or cut event and the largest tick-to-tick force step that followed it.
struct ForceEvent {
  double time_s = 0.0;      ///< loop time of the event, s
  double sim_time_s = 0.0;  ///< simulated time of the model that reported it, s
  std::uint32_t kind = 0;   ///< 1 = cut, 2 = contact change, 3 = both
  /// largest |F(k) - F(k-1)| over the 20 ms after it, any handle, rendered ticks only (a safety
  /// stop's drop to zero is not one: LoopTelemetry::zero_ticks counts those), N
  double max_step_N = 0.0;
  double max_jaw_step_Nm = 0.0;  ///< same for the jaw torque, N m
};

struct LoopTelemetry {
  static constexpr std::size_t kBins = 5000;  ///< 1 us bins of the tick period, 0 .. 5 ms
  static constexpr std::size_t kEvents = 256;

  double period_s = 1e-3;                          ///< nominal period
  std::array<std::uint64_t, kBins> period_hist{};  ///< tick periods, 1 us bins (last: >= 5 ms)
  /// Same, without the two periods around each platform stall (the late one and the short one
  /// after it): the loop's own timing quality with the host's pauses set apart.
  std::array<std::uint64_t, kBins> clean_hist{};
  std::uint64_t clean_periods = 0;
  std::uint64_t ticks = 0;               ///< ticks run
  std::uint64_t periods = 0;             ///< periods recorded (ticks - 1)
  std::uint64_t max_period_ns = 0;       ///< longest period seen
  std::uint64_t missed_deadlines = 0;    ///< deadlines skipped (not replayed) after late wake-ups
  std::uint64_t late_ticks = 0;          ///< periods longer than period + late_threshold
  std::uint64_t platform_stalls = 0;     ///< late ticks during which the gap monitor stalled too
  std::uint64_t loop_overruns = 0;       ///< late ticks after the loop's own tick ran > period/2
  std::uint64_t sched_delays = 0;        ///< late ticks explained by neither (the loop was
                                         ///< runnable but not run: IRQs, kernel, vCPU preemption
                                         ///< the monitor missed)
  std::uint64_t max_tick_work_ns = 0;    ///< longest time spent inside one tick
  std::uint64_t gaps = 0;                ///< periods beyond the watchdog (state reset, zero force)
  std::uint64_t monitor_gaps = 0;        ///< gaps the monitor thread itself observed
  std::uint64_t slew_limited_ticks = 0;  ///< ticks where the slew limit bounded the force
  std::uint64_t device_samples = 0;      ///< fresh device samples consumed
  std::uint64_t models = 0;              ///< new ContactModels taken
  std::array<std::uint64_t, static_cast<std::size_t>(ZeroReason::kCount)> zero_ticks{};
  std::array<ForceEvent, kEvents> events{};
  std::uint64_t n_events = 0;  ///< events recorded (the ring keeps the last kEvents)
  bool realtime = false;       ///< SCHED_FIFO granted
  int cpu = -1;                ///< pinned core, -1 if not pinned

  void record_period(std::int64_t ns) noexcept;
  void record_clean(std::int64_t ns) noexcept;
  /// Percentile p in [0,1] of the tick period, s (bin resolution 1 us). 0 when empty.
  [[nodiscard]] double period_percentile(double p) const noexcept;
  /// Percentile p of |period - nominal|, s; over all periods, or without platform stalls.
  [[nodiscard]] double jitter_percentile(double p, bool without_stalls = false) const noexcept;
  /// Largest |period - nominal| seen, s.
  [[nodiscard]] double max_jitter_s() const noexcept;
  /// Writes a JSON object (no trailing newline).
  void write_json(std::ostream& os) const;
};

}  // namespace serosa::haptics
