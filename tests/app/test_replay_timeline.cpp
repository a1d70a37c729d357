// The replay's metric timeline (app/replay_timeline.h): computed from a recording by replaying
// it, its force plot agrees with the run's own report, its error marks fall where the metrics
// counted the errors, and in the replay window (under Xvfb) the N key jumps to each.
#include <gtest/gtest.h>

#include <nlohmann/json.hpp>

#include <algorithm>
#include <fstream>
#include <regex>
#include <sstream>
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
      "headless " + shell_quote(source("config/appendectomy.toml").string()) + " --path " +
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

// The default scene with a force limit of 0.5 N (both the grasper and the scissors cross it),
// its relative paths made absolute.
fs::path strict_scene(const fs::path& dir) {
  std::ifstream in(source("config/appendectomy.toml"));
  std::ostringstream all;
  all << in.rdbuf();
  std::string text = all.str();
  const auto replace = [&](const std::string& from, const std::string& to) {
    for (auto at = text.find(from); at != std::string::npos; at = text.find(from, at + to.size()))
      text.replace(at, from.size(), to);
  };
  // Built with append: GCC 12 warns (-Wrestrict) about "x" + std::string here.
  const auto under = [](const char* head, const std::string& folder) {
    std::string to = head;
    to.append(source(folder).string()).append("/");
    return to;
  };
  replace("force_limit = 5.0", "force_limit = 0.5");
  replace("\"../assets/", under("\"", "assets"));
  replace("script:paths/", under("script:", "config/paths"));
  replace("\"assessment/", under("\"", "config/assessment"));
  const fs::path scene = dir / "strict.toml";
  std::ofstream(scene) << text;
  return scene;
}

// The position the replay window's title shows, s ("Serosa replay  2.53 / 5.00 s ...").
double title_position(const std::string& title) {
  std::smatch m;
  if (!std::regex_search(title, m, std::regex(R"(Serosa replay  ([0-9.]+) /)"))) return -1.0;
  return std::stod(m[1].str());
}

// In the replay window, once the timeline is known and the replay has played to its end, N jumps
// to a second before the first error, then to a second before the second (the grasper and the
// scissors both press harder than 0.5 N in the first 3.8 s).
TEST(ReplayTimeline, TheNKeyJumpsToEachErrorInTheWindow) {
  const fs::path dir = out_dir("replay_timeline_window");
  const fs::path recording = dir / "strict.lapr";
  const CliResult run = run_serosa("headless " + shell_quote(strict_scene(dir).string()) +
                                   " --steps 760 --record " + shell_quote(recording.string()));
  ASSERT_EQ(run.code, 0) << run.out;
  const TimelineData t = compute_timeline(recording, 400);
  ASSERT_GE(t.marks.size(), 2u);
  const Command window =
      run_command("xvfb-run -a -s '-screen 0 1280x720x24' " +
                  shell_quote(source("tests/app/jump_in_replay.sh").string()) + " " +
                  shell_quote(serosa_exe().string()) + " " + shell_quote(recording.string()));
  ASSERT_EQ(window.code, 0) << window.output;
  std::vector<std::string> titles;
  std::istringstream lines(window.output);
  for (std::string line; std::getline(lines, line);)
    if (line.rfind("Serosa replay", 0) == 0) titles.push_back(line);
  ASSERT_EQ(titles.size(), 2u) << window.output;
  for (std::size_t k = 0; k < 2; ++k) {
    SCOPED_TRACE(titles[k]);
    std::string shown = "error ";
    shown.append(std::to_string(k + 1)).append("/").append(std::to_string(t.marks.size()));
    EXPECT_NE(titles[k].find(shown), std::string::npos);
    EXPECT_NE(titles[k].find("[paused]"), std::string::npos);
    EXPECT_NEAR(title_position(titles[k]), std::max(t.marks[k].time_s - 1.0, 0.0), 0.006);
  }
}

TEST(ReplayTimeline, NextMarkIsTheFirstLaterOneAndWrapsRound) {
  const std::vector<render::TimelineMark> marks = {{1.0, "a"}, {2.5, "b"}, {4.0, "c"}};
  EXPECT_EQ(next_mark(marks, 0.0), 0u);
  EXPECT_EQ(next_mark(marks, 1.0), 1u);
  EXPECT_EQ(next_mark(marks, 3.0), 2u);
  EXPECT_EQ(next_mark(marks, 4.0), 0u);
  EXPECT_EQ(next_mark({}, 0.0), std::nullopt);
}

}  // namespace
}  // namespace serosa::app
