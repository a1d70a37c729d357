// Idle time reads a hand whatever drives it (metrics/metrics_stage.h kIdleWindowS): a tip moving
// at a steady 2 cm/s is at work whether its pose changes every solver step (a script, the rig's
// 1 kHz loop), once a frame at 8 frames/s (the mouse in a slow window) or every 0.1 s (a script
// from Python); a tip that stops is idle from about kIdleWindowS later; a restored stage goes on
// as the uninterrupted one.
#include <gtest/gtest.h>

#include <cmath>

#include "engine/sim_state.h"
#include "metrics/metrics_stage.h"
#include "support/block_copy.h"

namespace serosa::metrics {
namespace {

constexpr double kDt = 0.005;

Scene one_grasper() {
  Scene scene;
  scene.settings.dt_s = kDt;
  Tool grasper;
  grasper.name = "grasper";
  grasper.kind = ToolKind::kGrasper;
  scene.tools = {grasper};
  return scene;
}

// The grasper's input at step k when its hand moves at `speed` (m/s) until `stop_s` and its
// driver updates the pose every `every` steps.
ToolState input(std::uint64_t k, double speed, std::uint64_t every, double stop_s = 1e9) {
  const double t = std::min(static_cast<double>(k - k % every) * kDt, stop_s);
  ToolState s;
  s.tip_m = {speed * t, 0.0, 0.05};
  return s;
}

double idle_over(double seconds, double speed, std::uint64_t every, double stop_s = 1e9) {
  const LameTable table;
  MetricsStage m(one_grasper(), table);
  SimState s;
  const auto steps = static_cast<std::uint64_t>(std::lround(seconds / kDt));
  for (std::uint64_t k = 0; k < steps; ++k) {
    s.tools = {input(k, speed, every, stop_s)};
    m.step({k, static_cast<double>(k) * kDt, kDt}, s);
  }
  return m.idle_time_s();
}

TEST(IdleTime, AHandInMotionIsAtWorkWhateverDrivesIt) {
  for (const std::uint64_t every : {1u, 25u, 20u}) {  // every step, 8 frames/s, every 0.1 s
    const double idle = idle_over(10.0, 0.02, every);
    EXPECT_LT(idle, 0.03 * 10.0) << "a pose every " << every << " steps";
  }
  EXPECT_NEAR(idle_over(10.0, 0.0, 1), 10.0 - kDt, 1e-9);  // still: idle all along
}

TEST(IdleTime, AHandThatStopsIsIdleFromAWindowLater) {
  for (const std::uint64_t every : {1u, 25u}) {
    const double idle = idle_over(4.0, 0.02, every, 2.0);
    EXPECT_LE(idle, 2.0 + 1e-9) << every;
    EXPECT_GE(idle, 2.0 - kIdleWindowS - 0.125 - 2 * kDt) << every;
  }
}

TEST(IdleTime, ARestoredStageGoesOnAsTheUninterruptedOne) {
  const LameTable table;
  MetricsStage whole(one_grasper(), table);
  MetricsStage first(one_grasper(), table);
  SimState s, cut_short;  // the uninterrupted run's state, and the one stopped at 190 steps
  for (std::uint64_t k = 0; k < 300; ++k) {
    s.tools = {input(k, 0.02, 25, 1.0)};
    whole.step({k, static_cast<double>(k) * kDt, kDt}, s);
    cut_short.tools = s.tools;
    if (k < 190) first.step({k, static_cast<double>(k) * kDt, kDt}, cut_short);
  }
  SimState r;
  r.blocks.metrics = test_blocks::copy(cut_short.blocks.metrics);
  MetricsStage restored(one_grasper(), table);
  restored.adopt(r);
  for (std::uint64_t k = 190; k < 300; ++k) {
    r.tools = {input(k, 0.02, 25, 1.0)};
    restored.step({k, static_cast<double>(k) * kDt, kDt}, r);
  }
  EXPECT_GT(whole.idle_time_s(), 0.2);  // it stopped at 1 s, inside the window at the snapshot
  EXPECT_EQ(restored.idle_time_s(), whole.idle_time_s());
}

}  // namespace
}  // namespace serosa::metrics
