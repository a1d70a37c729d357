// The replay's timeline (replay/replay_timeline.h): computed from a recording by replaying it, its
// force plot agrees with the run's own report, its assessment is the run's, and its marks are
// exactly the criteria the run failed. (In the window: test_replay_timeline_window.cpp.)
#include <gtest/gtest.h>

#include <nlohmann/json.hpp>

#include <algorithm>
#include <fstream>
#include <set>
#include <string>

#include "app/session_summary.h"
#include "app_test_util.h"
#include "engine/shell_command.h"
#include "replay/replay_timeline.h"

namespace serosa::app {
namespace {

using namespace serosa::replay;

using namespace serosa::app::testing;

struct Recorded {
  fs::path recording;
  nlohmann::json report;
};

// `scene` run headless along `path` for `steps` steps, recorded.
Recorded record(const std::string& name, const std::string& scene, const std::string& path,
                int steps) {
  const fs::path dir = out_dir("replay_timeline_" + name);
  Recorded r{dir / "run.lapr", {}};
  const CliResult run = run_serosa(
      "headless " + shell_quote(source(scene).string()) + " --path " +
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

// The criteria a headless run's assessment failed on.
std::set<std::string> failed_criteria(const nlohmann::json& report) {
  std::set<std::string> names;
  for (const auto& [name, m] : report["assessment"]["metrics"].items())
    if (!m["passed"].get<bool>()) names.insert(name);
  return names;
}

// The replay's assessment is the run's: same score, same failures.
void expect_same_assessment(const TimelineData& t, const nlohmann::json& report) {
  ASSERT_TRUE(t.report.contains("assessment"));
  EXPECT_EQ(t.report["assessment"]["score"], report["assessment"]["score"]);
  EXPECT_EQ(t.report["assessment"]["failed"], report["assessment"]["failed"]);
}

// The expert's transection: the force plot's peak is the run's largest force, and a run that
// passes every criterion has nothing marked (its 5 N crossings are within the rubric's limits).
TEST(ReplayTimeline, TheForcePlotPeaksAtTheRunsLargestForceAndAPassHasNoMarks) {
  const Recorded run =
      record("expert", "config/transection.toml", "config/paths/appendectomy.csv", 1000);
  const TimelineData t = compute_timeline(run.recording, 400);
  ASSERT_TRUE(t.done);
  EXPECT_TRUE(t.error.empty()) << t.error;
  EXPECT_EQ(t.computed, t.steps);
  EXPECT_EQ(t.steps, run.report["steps_taken"].get<std::uint64_t>());
  const float peak = *std::max_element(t.force_n.begin(), t.force_n.end());
  EXPECT_NEAR(peak, largest_force(run.report), 1e-5 * largest_force(run.report));
  EXPECT_TRUE(std::none_of(t.force_n.begin(), t.force_n.end(), [](float f) { return f < 0.0f; }));
  ASSERT_GT(run.report["metrics"]["force_over_s"].get<double>(), 0.0);
  expect_same_assessment(t, run.report);
  ASSERT_TRUE(failed_criteria(run.report).empty());
  EXPECT_TRUE(t.marks.empty());
  EXPECT_TRUE(t.failures.empty());
}

#if !defined(__SANITIZE_ADDRESS__)  // the 12 s novice runs: ASan+UBSan is ~15x slower
std::set<std::string> marked_criteria(const TimelineData& t) {
  std::set<std::string> names;
  for (const render::TimelineMark& m : t.marks) names.insert(m.criterion);
  return names;
}

// The novice's transection strays from the planned line: its marks are exactly the criteria it
// failed, the cut off the line marked while the blades were in the tissue.
TEST(ReplayTimeline, TheNovicesTransectionMarksExactlyItsFailedCriteria) {
  const Recorded run =
      record("novice", "config/transection.toml", "config/paths/appendectomy_novice.csv", 2400);
  const TimelineData t = compute_timeline(run.recording, 400);
  ASSERT_TRUE(t.done);
  expect_same_assessment(t, run.report);
  ASSERT_TRUE(failed_criteria(run.report).contains("cut.collateral_m3"));
  EXPECT_EQ(marked_criteria(t), failed_criteria(run.report));
  for (const render::TimelineMark& m : t.marks) {
    EXPECT_GE(m.time_s, 0.0);
    EXPECT_LE(m.time_s, t.duration_s + 1e-9);
    if (m.criterion == "cut.collateral_m3") {
      EXPECT_NE(m.what.find("off the planned line"), std::string::npos) << m.what;
      EXPECT_LT(m.time_s, t.duration_s - 1.0);  // during the cut, not at the end
    }
  }
}

// The shipped procedure's novice (docs/procedure.md; the appendectomy task's scene and paths): the
// bleeding at 8.0 s, the steps it never did and the rest of what it failed are marked, nothing
// else; the expert's procedure has none.
TEST(ReplayTimeline, TheProcedureNovicesMarksAreItsFailedCriteriaAndTheExpertHasNone) {
  const Recorded novice = record("procedure_novice", "config/appendectomy.toml",
                                 "config/paths/appendectomy_procedure_novice.csv", 2820);
  const TimelineData t = compute_timeline(novice.recording, 400);
  ASSERT_TRUE(t.done);
  expect_same_assessment(t, novice.report);
  EXPECT_EQ(marked_criteria(t), failed_criteria(novice.report));
  const auto bleeding = std::find_if(t.marks.begin(), t.marks.end(), [](const auto& m) {
    return m.criterion == "bleeding_events";
  });
  ASSERT_NE(bleeding, t.marks.end());
  EXPECT_NEAR(bleeding->time_s, novice.report["metrics"]["errors"][0]["time_s"].get<double>(),
              1e-9);
  EXPECT_NEAR(bleeding->time_s, 8.0, 0.1);
  EXPECT_EQ(bleeding->what.rfind("bleeding", 0), 0u) << bleeding->what;
  EXPECT_TRUE(std::none_of(t.marks.begin(), t.marks.end(), [](const auto& m) {
    return m.what.find("planned line") != std::string::npos;  // judged for the transection only
  }));
  // The clip it closed on nothing, which fell away, is marked where its jaws closed.
  const auto clip = std::find_if(t.marks.begin(), t.marks.end(),
                                 [](const auto& m) { return m.criterion == "clips_on_artery"; });
  ASSERT_NE(clip, t.marks.end());
  EXPECT_EQ(novice.report["clips"]["dropped"]["clip-applier"].get<int>(), 1);
  EXPECT_GT(clip->time_s, 3.0);
  EXPECT_LT(clip->time_s, bleeding->time_s);
  for (const auto& m : t.marks) std::printf("mark %.3f s  %s\n", m.time_s, m.what.c_str());

  // The trainee's summary of the same run says the same in the same words: the critical
  // failures under "Why", the others under "To work on", the five steps, the metrics by domain.
  const render::SessionSummary s = session_summary(novice.report);
  const auto listed = [](const std::vector<std::string>& lines, const std::string& part) {
    return std::any_of(lines.begin(), lines.end(),
                       [&](const std::string& l) { return l.find(part) != std::string::npos; });
  };
  EXPECT_FALSE(s.passed);
  EXPECT_TRUE(listed(s.failed, "bleeding: the artery was cut before it was secured"));
  EXPECT_TRUE(listed(s.failed, "step not done: transect"));
  EXPECT_TRUE(listed(s.below, "clip missed"));
  ASSERT_EQ(s.steps.size(), 5u);
  EXPECT_EQ(s.steps[0].name, "expose");
  EXPECT_TRUE(s.steps[0].done);
  EXPECT_FALSE(s.steps[3].done);
  EXPECT_FALSE(s.groups.empty());

  const Recorded expert = record("procedure_expert", "config/appendectomy.toml",
                                 "config/paths/appendectomy_procedure.csv", 1880);
  const TimelineData e = compute_timeline(expert.recording, 400);
  ASSERT_TRUE(e.done);
  expect_same_assessment(e, expert.report);
  EXPECT_TRUE(e.marks.empty()) << e.marks.front().what;
}
#endif

TEST(ReplayTimeline, NextMarkIsTheFirstLaterOneAndWrapsRound) {
  const std::vector<render::TimelineMark> marks = {{1.0, "a", ""}, {2.5, "b", ""}, {4.0, "c", ""}};
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
  // P: the last mark whose landing point (a second before it) lies more than half a second
  // behind; from where a jump to it landed, the one before; wrapping round to the last.
  EXPECT_EQ(mark_to_jump_back_to(marks, 5.0), 2u);
  EXPECT_EQ(mark_to_jump_back_to(marks, 3.0), 2u - 1u);  // 3.0 lands at 2.0 < 2.5
  EXPECT_EQ(mark_to_jump_back_to(marks, 1.5), 1u - 1u);
  EXPECT_EQ(mark_to_jump_back_to(marks, 0.2), 2u);  // wraps round
  EXPECT_EQ(mark_to_jump_back_to({}, 1.0), std::nullopt);
}

}  // namespace
}  // namespace serosa::app
