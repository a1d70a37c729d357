// The replay's metric timeline (app/replay_timeline.h): computed from a recording by replaying
// it, its force plot agrees with the run's own report and its error marks fall where the metrics
// counted the errors. (In the window: test_replay_timeline_window.cpp.)
#include <gtest/gtest.h>

#include <nlohmann/json.hpp>

#include <algorithm>
#include <fstream>
#include <string>

#include "app/replay_timeline.h"
#include "app/shell_command.h"
#include "app_test_util.h"

namespace serosa::app {
namespace {

using namespace serosa::app::testing;

struct Recorded {
  fs::path recording;
  nlohmann::json report;
};

// The default scene run headless along `path` for `steps` steps, recorded.
Recorded record_default(const std::string& name, const std::string& path, int steps) {
  const fs::path dir = out_dir("replay_timeline_" + name);
  Recorded r{dir / "run.lapr", {}};
  const CliResult run = run_serosa(
      "headless " + shell_quote(source("config/transection.toml").string()) + " --path " +
      shell_quote(source(path).string()) + " --steps " + std::to_string(steps) + " --record " +
      shell_quote(r.recording.string()) + " --report " + shell_quote((dir / "r.json").string()));
  EXPECT_EQ(run.code, 0) << run.out;
  std::ifstream(dir / "r.json") >> r.report;
  return r;
}

double largest_force(const nlohmann::json& report) {
  double f = 0.0;
  for (const auto& [tool, v] : report["metrics"]["force_max_n"].items())
    f = std::max(f, v.get<double>());
  return f;
}

// The expert's default procedure: the grasper pulls harder than the scene's 5 N limit while it
// lifts the appendix; every time it crosses the limit is marked, and the force plot's peak is the
// run's largest force.
TEST(ReplayTimeline, MarksEachTimeAToolCrossesTheForceLimit) {
  const Recorded run = record_default("expert", "config/paths/appendectomy.csv", 1000);
  const TimelineData t = compute_timeline(run.recording, 400);
  ASSERT_TRUE(t.done);
  EXPECT_TRUE(t.error.empty()) << t.error;
  EXPECT_EQ(t.computed, t.steps);
  EXPECT_EQ(t.steps, run.report["steps_taken"].get<std::uint64_t>());
  const float peak = *std::max_element(t.force_n.begin(), t.force_n.end());
  EXPECT_NEAR(peak, largest_force(run.report), 1e-5 * largest_force(run.report));
  EXPECT_TRUE(std::none_of(t.force_n.begin(), t.force_n.end(), [](float f) { return f < 0.0f; }));
  ASSERT_GT(run.report["metrics"]["force_over_s"].get<double>(), 0.0);
  ASSERT_FALSE(t.marks.empty());
  for (std::size_t k = 0; k < t.marks.size(); ++k) {
    EXPECT_NE(t.marks[k].what.find("over 5 N"), std::string::npos) << t.marks[k].what;
    EXPECT_GE(t.marks[k].time_s, 0.0);
    EXPECT_LE(t.marks[k].time_s, t.duration_s);
    if (k > 0) {
      EXPECT_GE(t.marks[k].time_s, t.marks[k - 1].time_s);
    }
  }
}

#if !defined(__SANITIZE_ADDRESS__)  // the 12 s novice run: ASan+UBSan is ~15x slower
// The novice's cut strays from the planned line: each step that took tissue outside the band is
// marked, and the marks' volumes add up to the collateral the run reports.
TEST(ReplayTimeline, MarksTheCutsOffThePlannedLine) {
  const Recorded run = record_default("novice", "config/paths/appendectomy_novice.csv", 2400);
  const TimelineData t = compute_timeline(run.recording, 400);
  ASSERT_TRUE(t.done);
  double marked_mm3 = 0.0;
  for (const auto& m : t.marks) {
    if (m.what.rfind("cut ", 0) == 0) marked_mm3 += std::stod(m.what.substr(4));
  }
  const double collateral_mm3 = run.report["metrics"]["cut"]["collateral_m3"].get<double>() * 1e9;
  ASSERT_GT(collateral_mm3, 0.0);
  EXPECT_NEAR(marked_mm3, collateral_mm3, 0.01 * collateral_mm3);
}
#endif

TEST(ReplayTimeline, NextMarkIsTheFirstLaterOneAndWrapsRound) {
  const std::vector<render::TimelineMark> marks = {{1.0, "a"}, {2.5, "b"}, {4.0, "c"}};
  EXPECT_EQ(next_mark(marks, 0.0), 0u);
  EXPECT_EQ(next_mark(marks, 1.0), 1u);
  EXPECT_EQ(next_mark(marks, 3.0), 2u);
  EXPECT_EQ(next_mark(marks, 4.0), 0u);
  EXPECT_EQ(next_mark({}, 0.0), std::nullopt);
  // Jumping: after a jump to mark 1 (the replay a second before it, or at it), the next is 2;
  // played on past it, the next is the first later one; with no jump yet, the first ahead.
  EXPECT_EQ(mark_to_jump_to(marks, -1, 0.0), 0u);
  EXPECT_EQ(mark_to_jump_to(marks, 1, 1.5), 2u);
  EXPECT_EQ(mark_to_jump_to(marks, 1, 2.5), 2u);
  EXPECT_EQ(mark_to_jump_to(marks, 2, 3.0), 0u);  // wraps round
  EXPECT_EQ(mark_to_jump_to(marks, 0, 3.0), 2u);  // played on past mark 0 and mark 1
  EXPECT_EQ(mark_to_jump_to({}, -1, 0.0), std::nullopt);
}

}  // namespace
}  // namespace serosa::app
