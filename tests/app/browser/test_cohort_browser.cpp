// The cohort page end to end, as an instructor gets it: three trainees practise the three
// shortest tasks of the curriculum (camera, transfer, clip: their expert's and novice's scripted
// paths, `serosa headless --task --trainee`), `serosa cohort` writes the page and the CSV, and a
// real browser (Debian's chromium, headless, from the file system) renders it: the picture is not
// blank, the charts are drawn in the tasks' colours and the DOM names every trainee. A machine
// without chromium fails here (tools/debian-packages.txt installs it). Its own executable, run
// by CTest as trainee.cohort_page_in_browser, outside the sanitizer builds (tests/CMakeLists.txt).
#define STB_IMAGE_IMPLEMENTATION
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdlib>
#include <set>
#include <string>
#include <vector>

#include "app/app_test_util.h"
#include "app/read_png.h"
#include "trainee/cohort_markup.h"
#include "trainee/progress_db.h"
#include "trainee/task_list.h"

namespace serosa::app {
namespace {

using namespace serosa::trainee;

using namespace serosa::app::testing;

struct Practice {
  std::string trainee;
  std::string task;
  bool expert;
};

// Ann does every task as the expert, Bo as the novice and then the camera as the expert, Cy a
// mix: the camera passed by all three, the transfer by two, the clip by one.
const std::vector<Practice> kPractice{
    {"Ann Expert", "camera", true},   {"Ann Expert", "transfer", true},
    {"Ann Expert", "clip", true},     {"Bo Novice", "camera", false},
    {"Bo Novice", "transfer", false}, {"Bo Novice", "clip", false},
    {"Bo Novice", "camera", true},    {"Dr. Cy Mixed", "camera", false},
    {"Dr. Cy Mixed", "camera", true}, {"Dr. Cy Mixed", "transfer", true},
    {"Dr. Cy Mixed", "clip", false}};

const std::vector<std::string> kTrainees{"Ann Expert", "Bo Novice", "Dr. Cy Mixed"};
const std::vector<std::string> kTasks{"camera", "transfer", "clip"};

void practise(const fs::path& db) {
  const fs::path list = source("config/tasks.toml");
  const std::vector<Task> tasks = load_tasks(list);
  for (const Practice& p : kPractice) {
    const Task& t = find_task(tasks, p.task, list);
    const CliResult r =
        run_serosa("headless --task " + p.task + " --tasks " + shell_quote(list.string()) +
                   " --path " + shell_quote((p.expert ? t.expert : t.novice).string()) +
                   " --steps " + std::to_string(p.expert ? t.expert_steps : t.novice_steps) +
                   " --trainee " + shell_quote(p.trainee) + " --db " + shell_quote(db.string()));
    ASSERT_EQ(r.code, 0) << p.trainee << " " << p.task << "\n" << r.out;
  }
}

std::size_t count(const std::string& text, const std::string& what) {
  std::size_t n = 0;
  for (std::size_t at = 0; (at = text.find(what, at)) != std::string::npos; at += what.size()) ++n;
  return n;
}

// `chromium --headless ...` on the page; the test fails (not skips) when there is none.
CliResult chromium(const std::string& args, const fs::path& profile) {
  const Command which = run_command("command -v chromium");
  if (which.code != 0) return {-1, "chromium is not installed (tools/debian-packages.txt)"};
  const Command c = run_command(
      "timeout 120 chromium --headless --no-sandbox --disable-gpu "
      "--hide-scrollbars --user-data-dir=" +
      shell_quote(profile.string()) + " " + args);
  return {c.code, c.output};
}

void check_page_text(const std::string& page, const fs::path& db, const fs::path& dir) {
  for (const std::string& name : kTrainees)
    EXPECT_GE(count(page, name), 3u) << name;  // the table, the curves, the sessions
  for (const std::string& task : kTasks)
    EXPECT_NE(page.find("<th>" + task + "<br>"), std::string::npos) << task;
  EXPECT_EQ(count(page, "<svg class=\"curve\""), 3u);  // one learning curve per trainee
  EXPECT_EQ(count(page, "<svg class=\"bars\""), 1u);
  EXPECT_NE(page.find("3 of 3 trainees passed"), std::string::npos);
  EXPECT_NE(page.find("2 of 3 trainees passed"), std::string::npos);
  EXPECT_NE(page.find("1 of 3 trainees passed"), std::string::npos);
  EXPECT_NE(page.find("score under the pass score"), std::string::npos);
  for (const std::string& who : kTrainees)
    for (const SessionRecord& s : ProgressDb(db).sessions(who)) {
      ASSERT_TRUE(fs::exists(s.recording)) << s.recording;
      const std::string href = file_href(s.recording, dir);
      EXPECT_EQ(href.substr(0, 14), "../recordings/") << href;  // beside the page: relative
      EXPECT_NE(page.find("<a href=\"" + html_escape(href) + "\">"), std::string::npos) << href;
      EXPECT_NE(page.find(html_escape("serosa replay " + shell_quote(s.recording))),
                std::string::npos);
    }
}

void check_csv(const std::string& csv) {
  EXPECT_EQ(count(csv, "\n"), 1u + 3u * 3u) << csv;
  EXPECT_NE(csv.find("Ann Expert,clip,1,"), std::string::npos) << csv;
  EXPECT_NE(csv.find("Bo Novice,camera,2,"), std::string::npos) << csv;
  EXPECT_NE(csv.find(",yes,yes,1,80.0\nBo Novice"), std::string::npos) << csv;
}

// Not blank: much of it drawn, in many colours, the first task's colour (the camera's blue,
// #1f77b4) among them, so the SVG charts were drawn.
void check_picture(const fs::path& png) {
  const render::Image img = read_png(png);
  ASSERT_EQ(img.width, 1280) << png;
  ASSERT_EQ(img.height, 2000) << png;
  std::set<std::uint32_t> colours;
  std::size_t inked = 0, blue = 0;
  for (int y = 0; y < img.height; ++y)
    for (int x = 0; x < img.width; ++x) {
      const auto p = img.at(x, y);
      colours.insert(static_cast<std::uint32_t>(p[0]) << 16 |
                     static_cast<std::uint32_t>(p[1]) << 8 | p[2]);
      inked += (p[0] < 235 || p[1] < 235 || p[2] < 235) ? 1 : 0;
      blue +=
          (std::abs(p[0] - 0x1f) < 12 && std::abs(p[1] - 0x77) < 12 && std::abs(p[2] - 0xb4) < 12)
              ? 1
              : 0;
    }
  EXPECT_GT(colours.size(), 200u);
  EXPECT_GT(inked, static_cast<std::size_t>(img.width) * img.height / 50);
  EXPECT_GT(blue, 200u);
}

TEST(CohortBrowser, ThreeTraineesThreeTasksPageRendersInChromium) {
  const fs::path root = out_dir("cohort_browser");
  const fs::path db = root / "progress.sqlite", dir = root / "page", csv = root / "cohort.csv";
  practise(db);
  if (HasFatalFailure()) return;
  const CliResult r = run_serosa("cohort --db " + shell_quote(db.string()) + " --html " +
                                 shell_quote(dir.string()) + " --csv " + shell_quote(csv.string()));
  ASSERT_EQ(r.code, 0) << r.out;
  const std::string page = file_text(dir / "index.html");
  check_page_text(page, db, dir);
  check_csv(file_text(csv));

  const std::string url = "file://" + url_path((dir / "index.html").string());
  const fs::path png = root / "page.png";
  const CliResult shot = chromium(
      "--window-size=1280,2000 --screenshot=" + shell_quote(png.string()) + " " + shell_quote(url),
      root / "profile-shot");
  ASSERT_EQ(shot.code, 0) << shot.out;
  check_picture(png);
  const CliResult dom = chromium("--dump-dom " + shell_quote(url), root / "profile-dom");
  ASSERT_EQ(dom.code, 0) << dom.out;
  for (const std::string& name : kTrainees)
    EXPECT_NE(dom.out.find("<figcaption>" + name + "</figcaption>"), std::string::npos) << name;
  EXPECT_EQ(count(dom.out, "<polyline"), 3u * 3u);  // a line per trainee and task
}

}  // namespace
}  // namespace serosa::app
