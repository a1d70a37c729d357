#include "haptics/loop_telemetry.h"

#include <algorithm>
#include <cmath>
#include <vector>

namespace serosa::haptics {

void LoopTelemetry::record_period(std::int64_t ns) noexcept {
  if (ns < 0) ns = 0;
  const auto us = static_cast<std::size_t>(ns / 1000);
  ++period_hist[std::min(us, kBins - 1)];
  ++periods;
  max_period_ns = std::max(max_period_ns, static_cast<std::uint64_t>(ns));
}

void LoopTelemetry::record_clean(std::int64_t ns) noexcept {
  if (ns < 0) ns = 0;
  const auto us = static_cast<std::size_t>(ns / 1000);
  ++clean_hist[std::min(us, kBins - 1)];
  ++clean_periods;
}

double LoopTelemetry::period_percentile(double p) const noexcept {
  if (periods == 0) return 0.0;
  const auto target = static_cast<std::uint64_t>(std::ceil(std::clamp(p, 0.0, 1.0) * periods));
  std::uint64_t acc = 0;
  for (std::size_t i = 0; i < kBins; ++i) {
    acc += period_hist[i];
    if (acc >= std::max<std::uint64_t>(target, 1)) return (static_cast<double>(i) + 0.5) * 1e-6;
  }
  return static_cast<double>(kBins) * 1e-6;
}

double LoopTelemetry::jitter_percentile(double p, bool without_stalls) const noexcept {
  const auto& hist = without_stalls ? clean_hist : period_hist;
  const std::uint64_t count = without_stalls ? clean_periods : periods;
  if (count == 0) return 0.0;
  // Histogram of |bin centre - nominal| in 1 us steps.
  const auto nominal_us = static_cast<std::int64_t>(std::llround(period_s * 1e6));
  std::vector<std::uint64_t> jit(kBins + 1, 0);  // not on the loop thread
  for (std::size_t i = 0; i < kBins; ++i) {
    const auto d = static_cast<std::size_t>(std::llabs(static_cast<std::int64_t>(i) - nominal_us));
    jit[std::min(d, kBins)] += hist[i];
  }
  const auto target = std::max<std::uint64_t>(
      1, static_cast<std::uint64_t>(std::ceil(std::clamp(p, 0.0, 1.0) * count)));
  std::uint64_t acc = 0;
  for (std::size_t i = 0; i <= kBins; ++i) {
    acc += jit[i];
    if (acc >= target) return static_cast<double>(i) * 1e-6;
  }
  return static_cast<double>(kBins) * 1e-6;
}

double LoopTelemetry::max_jitter_s() const noexcept {
  if (periods == 0) return 0.0;
  return std::fabs(static_cast<double>(max_period_ns) * 1e-9 - period_s);
}

void LoopTelemetry::write_json(std::ostream& os) const {
  static constexpr const char* kReasons[] = {"none",     "unplugged",  "device_stale",
                                             "no_model", "not_finite", "gap"};
  os << "{\"period_s\":" << period_s << ",\"ticks\":" << ticks
     << ",\"realtime\":" << (realtime ? "true" : "false") << ",\"cpu\":" << cpu
     << ",\"period_p50_s\":" << period_percentile(0.5)
     << ",\"jitter_p50_s\":" << jitter_percentile(0.5)
     << ",\"jitter_p99_s\":" << jitter_percentile(0.99) << ",\"jitter_max_s\":" << max_jitter_s()
     << ",\"jitter_p99_without_stalls_s\":" << jitter_percentile(0.99, true)
     << ",\"missed_deadlines\":" << missed_deadlines << ",\"late_ticks\":" << late_ticks
     << ",\"platform_stalls\":" << platform_stalls << ",\"loop_overruns\":" << loop_overruns
     << ",\"sched_delays\":" << sched_delays
     << ",\"max_tick_work_s\":" << static_cast<double>(max_tick_work_ns) * 1e-9
     << ",\"gaps\":" << gaps << ",\"monitor_gaps\":" << monitor_gaps
     << ",\"slew_limited_ticks\":" << slew_limited_ticks << ",\"device_samples\":" << device_samples
     << ",\"models\":" << models << ",\"zero_ticks\":{";
  for (std::size_t i = 1; i < zero_ticks.size(); ++i) {
    os << (i > 1 ? "," : "") << '"' << kReasons[i] << "\":" << zero_ticks[i];
  }
  os << "},\"period_histogram_us\":[";
  bool first = true;
  for (std::size_t i = 0; i < kBins; ++i) {
    if (period_hist[i] == 0) continue;
    os << (first ? "" : ",") << '[' << i << ',' << period_hist[i] << ']';
    first = false;
  }
  os << "],\"force_events\":[";
  const std::uint64_t n = std::min<std::uint64_t>(n_events, kEvents);
  for (std::uint64_t k = 0; k < n; ++k) {
    const ForceEvent& e = events[(n_events - n + k) % kEvents];
    os << (k ? "," : "") << "{\"time_s\":" << e.time_s << ",\"sim_time_s\":" << e.sim_time_s
       << ",\"kind\":" << e.kind << ",\"max_step_N\":" << e.max_step_N
       << ",\"max_jaw_step_Nm\":" << e.max_jaw_step_Nm << '}';
  }
  os << "]}";
}

}  // namespace serosa::haptics
