// The overlay's numbers and text come from the frame's statistics: solver timing, the haptic
// loop's telemetry (a dash when no loop runs), cuts, the replay position and the metrics report.
#include <gtest/gtest.h>

#include "haptics/loop_telemetry.h"
#include "render/overlay.h"
#include "window/overlay_stats.h"

namespace serosa::app {
namespace {

TEST(OverlayStats, HapticRateIsTheMedianTickRateAndADashWithoutALoop) {
  window::FrameStats s;
  s.sim_time_s = 2.0;
  s.fem_ms_per_step = 4.5;
  s.solver_rate_hz = 180.0;
  s.cuts = 2;
  render::OverlayData d = window::overlay_data(s);
  EXPECT_EQ(d.haptic_rate_hz, 0.0);
  EXPECT_EQ(render::overlay_text(d).stats[2], "haptics \u2014");
  EXPECT_EQ(render::overlay_text(d).stats[1], "FEM 4.50 ms/step  (180 steps/s)");
  EXPECT_EQ(render::overlay_text(d).stats[3], "cuts 2");

  // A loop that ticked at 1 kHz with a few late ticks: the median says 1 kHz.
  auto t = std::make_unique<haptics::LoopTelemetry>();
  for (int i = 0; i < 990; ++i) t->record_period(1'000'000);
  for (int i = 0; i < 10; ++i) t->record_period(4'000'000);
  s.haptics = t.get();
  d = window::overlay_data(s);
  EXPECT_NEAR(d.haptic_rate_hz, 1000.0, 1.0);
  EXPECT_EQ(render::overlay_text(d).stats[2], "haptics 1000 Hz");
  // A loop that ran at 500 Hz.
  auto slow = std::make_unique<haptics::LoopTelemetry>();
  for (int i = 0; i < 100; ++i) slow->record_period(2'000'000);
  EXPECT_NEAR(window::haptic_rate_hz(*slow), 500.0, 0.5);
  // A loop that has not ticked twice yet: no rate.
  EXPECT_EQ(window::haptic_rate_hz(haptics::LoopTelemetry{}), 0.0);
}

TEST(OverlayStats, TheOverlaySaysWhatDrivesTheInstruments) {
  EXPECT_STREQ(window::instruments_label(DeviceKind::kMouse, true, true), "mouse");
  EXPECT_STREQ(window::instruments_label(DeviceKind::kRig, true, false), "rig");
  EXPECT_STREQ(window::instruments_label(DeviceKind::kRig, false, false), "rig not connected");
  EXPECT_STREQ(window::instruments_label(DeviceKind::kRig, false, false, true), "rig disconnected");
  EXPECT_STREQ(window::instruments_label(DeviceKind::kRigEmulated, false, false, true),
               "emulated rig disconnected");
  EXPECT_STREQ(window::instruments_label(DeviceKind::kRig, true, false, true), "rig");
  EXPECT_STREQ(window::instruments_label(DeviceKind::kRigEmulated, false, false),
               "emulated rig not connected");
  EXPECT_STREQ(window::instruments_label(DeviceKind::kScript, true, true), "script");
  EXPECT_STREQ(window::instruments_label(std::nullopt, false, true), "script");
  EXPECT_EQ(window::instruments_label(std::nullopt, false, false), nullptr);

  window::FrameStats s;
  s.haptic_live_rate_hz = 998.0;
  s.instruments = window::instruments_label(DeviceKind::kRig, false, false);
  EXPECT_EQ(render::overlay_text(window::overlay_data(s)).stats[2],
            "haptics 998 Hz  (rig not connected)");
  s.haptic_live_rate_hz = 0.0;
  s.instruments = window::instruments_label(std::nullopt, false, true);
  EXPECT_EQ(render::overlay_text(window::overlay_data(s)).stats[2], "haptics \u2014  (script)");
}

TEST(OverlayStats, ReplayAndMetricsReachTheOverlay) {
  const nlohmann::json report = {{"time_s", 3.5},
                                 {"path_length_m", {{"grasper", 0.25}, {"scissors", 0.125}}},
                                 {"force_max_n", {{"scissors", 1.5}}},
                                 {"peak_stress_pa", 2500.0},
                                 {"cut", {{"tets", 12}, {"volume_m3", 2e-7}}}};
  window::FrameStats s;
  s.replay = true;
  s.replay_position_s = 3.5;
  s.replay_duration_s = 5.0;
  s.replay_speed = 0.5;
  s.paused = true;
  s.metrics = &report;
  const render::OverlayData d = window::overlay_data(s);
  EXPECT_TRUE(d.replay);
  EXPECT_EQ(render::overlay_text(d).timeline, "0:03.5 / 0:05.0  x0.5  [paused]");
  ASSERT_EQ(d.metrics.size(), 7u);  // nlohmann orders object keys alphabetically
  EXPECT_EQ(d.metrics[0].name, "cut tets");
  EXPECT_EQ(d.metrics[0].value, 12.0);
  EXPECT_EQ(d.metrics[0].unit, "");
  EXPECT_EQ(d.metrics[1].name, "cut volume");
  EXPECT_EQ(d.metrics[1].unit, "m^3");
  EXPECT_EQ(d.metrics[2].name, "force max scissors");
  EXPECT_EQ(d.metrics[2].unit, "N");
  EXPECT_EQ(d.metrics[3].name, "path length grasper");
  EXPECT_EQ(d.metrics[3].value, 0.25);
  EXPECT_EQ(d.metrics[3].unit, "m");
  EXPECT_EQ(d.metrics[5].name, "peak stress");
  EXPECT_EQ(d.metrics[5].unit, "Pa");
  EXPECT_EQ(d.metrics[6].name, "time");
  EXPECT_EQ(d.metrics[6].unit, "s");
  const auto text = render::overlay_text(d);
  ASSERT_EQ(text.stats.size(), 4u + 7u);
  EXPECT_EQ(text.stats[4 + 3], "path length grasper 0.25 m");
}

}  // namespace
}  // namespace serosa::app
