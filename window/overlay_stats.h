// The overlay's numbers (render/render_frame.h OverlayData) from what the app measures: solver
// timing, the haptic loop's telemetry when a loop runs, cuts, replay position and the metrics
// report (metrics/metrics_stage.h). Plain data, no GL: tests check the values and the text.
#pragma once

#include <cstdint>
#include <optional>
#include <vector>

#include <nlohmann/json.hpp>

#include "engine/scene/scene.h"
#include "render/render_frame.h"

namespace serosa::haptics {
struct LoopTelemetry;
}

namespace serosa::window {

/// What one published frame says about the run.
struct FrameStats {
  double sim_time_s = 0.0;        ///< simulated time, s
  double fem_ms_per_step = 0.0;   ///< mean wall time of recent solver steps, ms
  double solver_rate_hz = 0.0;    ///< solver steps per wall second, Hz
  double real_time_factor = 0.0;  ///< simulated over wall seconds, the last second; 0: unknown
  /// The haptic loop's telemetry, null when no haptic loop runs (the overlay then shows a dash).
  const haptics::LoopTelemetry* haptics = nullptr;
  /// The haptic loop's live rate while it runs (its telemetry is the loop thread's then): ticks
  /// of its LoopStatus per wall second, Hz. Shown when `haptics` is null; 0: no loop (a dash).
  double haptic_live_rate_hz = 0.0;
  const char* instruments = nullptr;  ///< instruments_label(), shown beside the haptic rate
  std::int64_t cuts = 0;              ///< topology changes applied so far
  bool paused = false;
  bool slow_motion = false;
  /// Replay (instructors): position and length of the recording, s, and the playback speed.
  bool replay = false;
  double replay_position_s = 0.0;
  double replay_duration_s = 0.0;
  double replay_speed = 1.0;
  /// The metrics report (MetricsStage::report()), or null: listed for instructors.
  const nlohmann::json* metrics = nullptr;
};

/// What drives the instruments, as the overlay says it (a string literal): the haptic loop's
/// device when a loop runs ("mouse", "script", "rig" or "emulated rig", each rig with " not
/// connected" while it has never been there, " disconnected" once it was and is gone), else
/// "script" when a tool is scripted; null otherwise.
[[nodiscard]] const char* instruments_label(std::optional<DeviceKind> loop_device, bool connected,
                                            bool scripted, bool was_connected = false);

/// The haptic loop's rate, Hz: 1 / the median tick period; 0 when it has recorded no period.
[[nodiscard]] double haptic_rate_hz(const haptics::LoopTelemetry& telemetry);

/// The metrics report as overlay lines, in report order: every numeric leaf, named by its path
/// with underscores as spaces and the unit suffix (_m, _m3, _n, _pa, _s) taken off as its unit:
/// {"path_length_m": {"scissors": 0.12}} -> {"path length scissors", 0.12, "m"}.
[[nodiscard]] std::vector<render::OverlayMetric> overlay_metrics(const nlohmann::json& report);

/// The overlay's data for these stats.
[[nodiscard]] render::OverlayData overlay_data(const FrameStats& stats);

}  // namespace serosa::window
