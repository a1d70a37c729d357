// The instructor's replay window under Xvfb (replay/replay_window.cpp): a failed novice's debrief
// (app/session_summary.h) stands beside the picture once the timeline has assessed the recording,
// within its quarter of the view and off the timeline.
#include <gtest/gtest.h>

#include <nlohmann/json.hpp>

#include <algorithm>
#include <array>
#include <cstdint>
#include <cstdlib>
#include <fstream>
#include <string>

#include "app_test_util.h"
#include "engine/shell_command.h"
#include "read_png.h"
#include "render/session_summary.h"

namespace serosa::app {
namespace {

using namespace serosa::app::testing;

#if !defined(__SANITIZE_THREAD__) && !defined(__SANITIZE_ADDRESS__)  // an 8.5 s run, replayed twice
// The shipped procedure's novice up to 8.5 s (its bleeding at 8.0 s), recorded once per test
// process into the test's own folder: CTest runs the tests of this file side by side, and a
// shared file would be written by one while the other reads it.
fs::path novice_recording() {
  static const fs::path recording = [] {
    const fs::path file = own_dir("replay_debrief_novice") / "novice.lapr";
    const CliResult run = run_serosa(
        "headless " + shell_quote(source("config/appendectomy.toml").string()) + " --path " +
        shell_quote(source("config/paths/appendectomy_procedure_novice.csv").string()) +
        " --steps 1700 --record " + shell_quote(file.string()));
    EXPECT_EQ(run.code, 0) << run.out;
    return file;
  }();
  return recording;
}

bool overlaps(const nlohmann::json& a, const nlohmann::json& b) {
  return a[0].get<double>() < b[2].get<double>() && b[0].get<double>() < a[2].get<double>() &&
         a[1].get<double>() < b[3].get<double>() && b[1].get<double>() < a[3].get<double>();
}

bool has_line(const nlohmann::json& lines, const std::string& part) {
  return std::any_of(lines.begin(), lines.end(), [&](const nlohmann::json& l) {
    return l.get<std::string>().find(part) != std::string::npos;
  });
}

// The shipped procedure's novice, replayed in the window: beside the picture its debrief gives
// the verdict, the failed criteria in words (the bleeding at 0:08.0 among them) and the
// procedure's steps; the panels keep to their places (the debrief within a quarter of the width,
// none over the timeline), and the picture shows the verdict's red banner.
TEST(ReplayDebrief, ANovicesDebriefStandsBesideThePictureAndLeavesTheTimelineClear) {
  const fs::path dir = out_dir("replay_debrief_window");
  const fs::path recording = novice_recording();
  ASSERT_TRUE(fs::exists(recording));
  const fs::path png = dir / "last.png";
  const fs::path json = dir / "layout.json";
  const Command window =
      run_command("xvfb-run -a -s '-screen 0 1280x720x24' " +
                  shell_quote(source("tests/app/debrief_in_replay.sh").string()) + " " +
                  shell_quote(serosa_exe().string()) + " " + shell_quote(recording.string()) + " " +
                  shell_quote(png.string()) + " " + shell_quote(json.string()));
  ASSERT_EQ(window.code, 0) << window.output;
  nlohmann::json layout;
  std::ifstream(json) >> layout;
  const nlohmann::json& text = layout["debrief_text"];
  ASSERT_FALSE(text.empty()) << layout.dump(1);
  EXPECT_TRUE(has_line(text, "NOT PASSED"));
  EXPECT_TRUE(has_line(text, "0:08.0  bleeding: the artery was cut before it was secured"));
  EXPECT_TRUE(has_line(text, "step not done: transect"));
  for (const char* step : {"expose  0:00.0", "divide mesentery  0:02.8", "transect  not done"})
    EXPECT_TRUE(has_line(text, step)) << step;
  EXPECT_NE(layout["errors_line"].get<std::string>().find("N: next"), std::string::npos);
  const double width = layout["window"][0].get<double>();
  const nlohmann::json& debrief = layout["debrief"];
  EXPECT_LE(debrief[2].get<double>() - debrief[0].get<double>(), 0.25 * width);
  EXPECT_FALSE(overlaps(debrief, layout["replay_bar"])) << layout.dump();
  EXPECT_FALSE(overlaps(layout["statistics"], layout["replay_bar"])) << layout.dump();
  EXPECT_FALSE(overlaps(layout["debrief"], layout["statistics"])) << layout.dump();
  // The banner is drawn where the debrief says it is.
  const render::Image img = read_png(png);
  std::size_t red = 0;
  for (int y = static_cast<int>(debrief[1].get<double>()); y < debrief[3].get<double>(); ++y)
    for (int x = static_cast<int>(debrief[0].get<double>()); x < debrief[2].get<double>(); ++x) {
      const std::array<std::uint8_t, 4> p = img.at(x, y);
      const auto near = [](std::uint8_t a, unsigned char b) { return std::abs(a - b) < 8; };
      red += near(p[0], render::kFailedRgb[0]) && near(p[1], render::kFailedRgb[1]) &&
             near(p[2], render::kFailedRgb[2]);
    }
  EXPECT_GT(red, 3000u);
}

// Taken over at 7.5 s, before the novice's hook cuts the artery, and left at rest: the branch is
// scored on its own (its report beside its recording, no bleeding in it), and its timeline and
// debrief are its own (no bleeding marked; the debrief says it is the branch's).
TEST(ReplayDebrief, ABranchIsScoredOnItsOwn) {
  const fs::path dir = out_dir("replay_debrief_branch");
  const fs::path branch = dir / "branch.lapr";
  const fs::path json = dir / "layout.json";
  fs::remove(branch.parent_path() / "branch.json");
  const Command window = run_command(
      "xvfb-run -a -s '-screen 0 1280x720x24' " + shell_quote(serosa_exe().string()) + " replay " +
      shell_quote(novice_recording().string()) +
      " --speed 4 --branch-at 7.5 --seconds 20 --branch " + shell_quote(branch.string()) +
      " --layout-log " + shell_quote(json.string()) + " 2>&1");
  ASSERT_EQ(window.code, 0) << window.output;
  nlohmann::json report;
  std::ifstream(dir / "branch.json") >> report;
  ASSERT_TRUE(report.contains("assessment")) << window.output;
  const std::uint64_t at = report["branch_step"].get<std::uint64_t>();
  EXPECT_GE(at, 1500u);
  EXPECT_LT(at, 1605u);  // before the recorded bleeding's step
  EXPECT_EQ(report["metrics"]["bleeding_events"].get<int>(), 0);
  EXPECT_GT(report["steps"].get<std::uint64_t>(), at);
  nlohmann::json layout;
  std::ifstream(json) >> layout;
  for (const nlohmann::json& m : layout["marks"])
    EXPECT_NE(m["criterion"].get<std::string>(), "bleeding_events") << m.dump();
  ASSERT_FALSE(layout["debrief_text"].empty());
  EXPECT_EQ(layout["debrief_text"][0].get<std::string>().rfind("Branch so far: ", 0), 0u);
}
#endif

}  // namespace
}  // namespace serosa::app
