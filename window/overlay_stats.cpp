#include "window/overlay_stats.h"

#include <array>
#include <string>
#include <string_view>

#include "haptics/loop_telemetry.h"

namespace serosa::window {
namespace {

struct Suffix {
  std::string_view suffix;
  std::string_view unit;
};
constexpr std::array<Suffix, 5> kUnits{
    {{"_m3", "m^3"}, {"_pa", "Pa"}, {"_m", "m"}, {"_n", "N"}, {"_s", "s"}}};

// Appends `key` to `name` with underscores as spaces; returns the unit its suffix named.
std::string_view append_key(std::string& name, std::string_view key) {
  std::string_view unit;
  for (const Suffix& s : kUnits)
    if (key.size() > s.suffix.size() && key.ends_with(s.suffix)) {
      key.remove_suffix(s.suffix.size());
      unit = s.unit;
      break;
    }
  if (!name.empty()) name.push_back(' ');
  for (const char c : key) name.push_back(c == '_' ? ' ' : c);
  return unit;
}

void flatten(const nlohmann::json& j, const std::string& name, std::string_view unit,
             std::vector<render::OverlayMetric>& out) {
  if (j.is_object()) {
    for (const auto& [key, value] : j.items()) {
      std::string child;
      child.reserve(name.size() + key.size() + 1);
      child.append(name);
      const std::string_view u = append_key(child, key);
      flatten(value, child, u.empty() ? unit : u, out);
    }
  } else if (j.is_number()) {
    out.push_back({name, j.get<double>(), std::string(unit)});
  }
}

}  // namespace

const char* instruments_label(std::optional<DeviceKind> loop_device, bool connected, bool scripted,
                              bool was_connected) {
  if (!loop_device) return scripted ? "script" : nullptr;
  switch (*loop_device) {
    case DeviceKind::kMouse:
      return "mouse";
    case DeviceKind::kScript:
      return "script";
    case DeviceKind::kPython:
      return "python";
    case DeviceKind::kRig:
      return connected ? "rig" : was_connected ? "rig disconnected" : "rig not connected";
    case DeviceKind::kRigEmulated:
      return connected       ? "emulated rig"
             : was_connected ? "emulated rig disconnected"
                             : "emulated rig not connected";
  }
  return nullptr;
}

double haptic_rate_hz(const haptics::LoopTelemetry& telemetry) {
  if (telemetry.periods == 0) return 0.0;
  const double median = telemetry.period_percentile(0.5);
  return median > 0.0 ? 1.0 / median : 0.0;
}

std::vector<render::OverlayMetric> overlay_metrics(const nlohmann::json& report) {
  std::vector<render::OverlayMetric> out;
  flatten(report, "", "", out);
  return out;
}

render::OverlayData overlay_data(const FrameStats& s) {
  render::OverlayData o;
  o.sim_time_s = s.sim_time_s;
  o.fem_ms_per_step = s.fem_ms_per_step;
  o.solver_rate_hz = s.solver_rate_hz;
  o.real_time_factor = s.real_time_factor;
  o.haptic_rate_hz = s.haptics != nullptr ? haptic_rate_hz(*s.haptics) : s.haptic_live_rate_hz;
  o.instruments = s.instruments;
  o.cuts = s.cuts;
  o.paused = s.paused;
  o.slow_motion = s.slow_motion;
  o.replay = s.replay;
  o.replay_position_s = s.replay_position_s;
  o.replay_duration_s = s.replay_duration_s;
  o.replay_speed = s.replay_speed;
  if (s.metrics != nullptr) o.metrics = overlay_metrics(*s.metrics);
  return o;
}

}  // namespace serosa::window
