// The stapler variant of the appendectomy, run as a user runs it (`serosa headless
// config/appendectomy_stapler.toml --report R.json --export-final F.msh`): the scripted path does
// the five steps, the stapler securing and transecting the base in one fire (its two lines on
// the appendix, one on each piece, the knife between them), without an error, leaving the freed
// specimen with most of the appendix, and the session passes the scene's rubric. The report and
// the final mesh go to <build>/test-output/app/stapler_appendectomy/.
#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <string>

#include <nlohmann/json.hpp>

#include "app/app_test_util.h"
#include "procedure_checks.h"

namespace serosa::app {
namespace {

using testing::out_dir;
using testing::source;

using testing::lists;

TEST(StaplerAppendectomy, TheStaplerSecuresAndTransectsTheBaseInOneFire) {
  const std::filesystem::path dir = out_dir("stapler_appendectomy");
  const std::filesystem::path report = dir / "report.json", final_mesh = dir / "final.msh";
  const auto run = testing::run_serosa(
      "headless " + shell_quote(source("config/appendectomy_stapler.toml").string()) +
      " --report " + shell_quote(report.string()) + " --export-final " +
      shell_quote(final_mesh.string()));
  ASSERT_EQ(run.code, 0) << run.out;
  nlohmann::json r;
  std::ifstream(report) >> r;

  // The five steps, in their order; the base secured and transected by the stapler together.
  const auto& p = r["metrics"]["procedure"];
  EXPECT_TRUE(p["completed"].get<bool>()) << p.dump();
  const char* names[] = {"expose", "divide_mesentery", "secure_base", "transect", "extract"};
  const char* tools[] = {"grasper", "hook", "stapler", "stapler", "grasper"};
  ASSERT_EQ(p["steps"].size(), 5u);
  for (std::size_t i = 0; i < 5; ++i) {
    const auto& s = p["steps"][i];
    EXPECT_EQ(s["name"], names[i]);
    ASSERT_TRUE(s["done"].get<bool>()) << s.dump();
    EXPECT_EQ(s["tool"], tools[i]) << s.dump();
  }
  EXPECT_EQ(p["steps"][2]["time_s"], p["steps"][3]["time_s"]);  // one fire
  EXPECT_GE(p["specimen_volume_fraction"].get<double>(), 0.8);
  EXPECT_LT(p["specimen_volume_fraction"].get<double>(), 1.0);

  // The clip on the artery, then the two staple lines on the appendix, laid together.
  const auto& placed = r["clips"]["placed"];
  ASSERT_EQ(placed.size(), 3u) << r["clips"].dump();
  EXPECT_EQ(placed[0]["kind"], "clip");
  EXPECT_TRUE(lists(placed[0]["groups"], "artery")) << placed[0].dump();
  for (std::size_t k = 1; k < 3; ++k) {
    EXPECT_EQ(placed[k]["tool"], "stapler");
    EXPECT_EQ(placed[k]["kind"], "staple");
    EXPECT_TRUE(lists(placed[k]["groups"], "appendix")) << placed[k].dump();
    EXPECT_FALSE(lists(placed[k]["groups"], "cecum")) << placed[k].dump();
    // Laid at the start of the step whose end the steps are dated by (dt = 5 ms).
    EXPECT_NEAR(placed[k]["time_s"].get<double>(), p["steps"][3]["time_s"].get<double>() - 0.005,
                1e-9);
  }
  EXPECT_EQ(r["clips"]["dropped"]["stapler"], 0);
  EXPECT_EQ(r["clips"]["refused"]["stapler"], 0);
  EXPECT_EQ(r["cutting"]["stapler_fires"], 1);
  EXPECT_EQ(r["cutting"]["stapler_fires_held"], 0);

  // No error, and cutting conserved the volume of a valid (welded) mesh.
  testing::expect_clean_procedure(r);
  ASSERT_TRUE(std::filesystem::exists(final_mesh));

  // Scored on the procedure's rubric: every step done, a pass.
  const auto& a = r["assessment"];
  EXPECT_TRUE(a["passed"].get<bool>()) << a.dump();
  EXPECT_EQ(a["metrics"]["procedure.steps_done"]["value"].get<double>(), 5.0);
}

}  // namespace
}  // namespace serosa::app
