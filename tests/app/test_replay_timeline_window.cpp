// The replay window's metric timeline under Xvfb (replay/replay_timeline.h, built on a thread of
// its own beside the window's replay): once it is known, the N key jumps to each error.
#include <gtest/gtest.h>

#include <algorithm>
#include <fstream>
#include <sstream>
#include <string>

#include "app_test_util.h"
#include "engine/shell_command.h"
#include "replay/replay_timeline.h"

namespace serosa::app {
namespace {

using namespace serosa::replay;

using namespace serosa::app::testing;

std::string file_text(const fs::path& file) {
  std::ifstream in(file);
  std::ostringstream all;
  all << in.rdbuf();
  return all.str();
}

void replace_all(std::string& text, const std::string& from, const std::string& to) {
  for (auto at = text.find(from); at != std::string::npos; at = text.find(from, at + to.size()))
    text.replace(at, from.size(), to);
}

// The transection's rubric with a grasp of 1 N and 2 s as their limits: the expert's first 3.8 s
// fail both, the grasp where the grasper pulls hardest, the time at the end.
fs::path strict_rubric(const fs::path& dir) {
  std::string text = file_text(source("config/assessment/appendectomy.toml"));
  replace_all(text, "good = 12.0\npoor = 30.0\nlimit = 20.0",
              "good = 0.5\npoor = 2.0\nlimit = 1.0");
  replace_all(text, "good = 4.0\npoor = 15.0\nlimit = 10.0", "good = 1.0\npoor = 3.0\nlimit = 2.0");
  const fs::path rubric = dir / "strict_rubric.toml";
  std::ofstream(rubric) << text;
  return rubric;
}

// The transection scene scored by strict_rubric, its relative paths made absolute.
fs::path strict_scene(const fs::path& dir) {
  std::ifstream in(source("config/transection.toml"));
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
  replace("\"../assets/", under("\"", "assets"));
  replace("script:paths/", under("script:", "config/paths"));
  replace("\"assessment/appendectomy.toml\"",
          std::string("\"").append(strict_rubric(dir).string()).append("\""));
  const fs::path scene = dir / "strict.toml";
  std::ofstream(scene) << text;
  return scene;
}

// The position the replay window's title shows, s ("Serosa replay  2.53 / 5.00 s ...").
double title_position(const std::string& title) {
  // (No std::regex: under ASan GCC 12 warns inside it, maybe-uninitialized, a false positive.)
  const std::string head = "Serosa replay  ";
  if (title.rfind(head, 0) != 0 || title.find(" /", head.size()) == std::string::npos) return -1.0;
  return std::stod(title.substr(head.size()));
}

// In the replay window, once the timeline is known and the replay has played to its end, N jumps
// to a second before the first error, then to a second before the second (the strict rubric's
// grasp and time).
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

}  // namespace
}  // namespace serosa::app
