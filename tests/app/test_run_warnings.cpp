// A run that did not do what its scene asked says so (app/run_warnings.h): a solver that stops
// above its tolerance and a fixed box that selects nothing are warnings on stderr and in the
// report, naming the first step and the figures, and `--strict` turns them into exit 4 with the
// report still written; a run with neither is silent, strict or not.
#include <gtest/gtest.h>

#include <fstream>
#include <string>

#include <nlohmann/json.hpp>

#include "app/shell_command.h"
#include "app_test_util.h"

namespace serosa::app {
namespace {

using namespace serosa::app::testing;

// The bead on its own, held by a box at one end under gravity, as an engineer's first scene.
fs::path bead_scene(const fs::path& dir, const std::string& box, const std::string& solver) {
  const fs::path scene = dir / "scene.toml";
  std::ofstream(scene) << "[scene]\ndt = 0.005\neffects = [\"fem\", \"gravity\"]\n"
                       << "[[organ]]\nname = \"bead\"\nmesh = \""
                       << source("assets/bead.msh").string() << "\"\n"
                       << "young = 5.0e4\npoisson = 0.45\ndensity = 1.1e3\n"
                       << "fixed = { box = " << box << " }\n"
                       << solver << "[headless]\nsteps = 40\n";
  return scene;
}

nlohmann::json read_report(const fs::path& p) {
  nlohmann::json j;
  std::ifstream(p) >> j;
  return j;
}

// The box round the bead's -x end (the bead spans x from -31 to -19 mm).
const std::string kEndBox = "[[-0.1, -0.1, -0.1], [-0.0295, 0.1, 0.1]]";
const std::string kFarBox = "[[0.5, 0.5, 0.5], [0.6, 0.6, 0.6]]";
const std::string kCapped = "[solver]\nkind = \"pcg\"\ntolerance = 1e-9\nmax_iterations = 2\n";
const std::string kSound = "[solver]\nkind = \"pcg-lagged\"\ntolerance = 1e-3\n";

TEST(RunWarnings, AnEmptyFixedBoxIsSaidBeforeTheRunAndFailsUnderStrict) {
  const fs::path dir = out_dir("warn_box");
  const fs::path scene = bead_scene(dir, kFarBox, kSound);
  const std::string cmd = "headless " + shell_quote(scene.string()) + " --report " +
                          shell_quote((dir / "r.json").string());
  const CliResult plain = run_serosa(cmd);
  EXPECT_EQ(plain.code, 0) << plain.out;
  EXPECT_NE(plain.out.find("warning: " + scene.string() +
                           ": organ[0].fixed.box of organ 'bead' "
                           "selects no node"),
            std::string::npos)
      << plain.out;
  const nlohmann::json r = read_report(dir / "r.json");
  EXPECT_EQ(r["fixed"]["nodes"], 0) << r["fixed"].dump();
  EXPECT_EQ(r["fixed"]["organs"][0]["box"], 0);
  ASSERT_EQ(r["warnings"].size(), 1u) << r["warnings"].dump(1);
  EXPECT_EQ(r["warnings"][0]["kind"], "empty_selection");

  fs::remove(dir / "r.json");
  const CliResult strict = run_serosa(cmd + " --strict");
  EXPECT_EQ(strict.code, 4) << strict.out;
  EXPECT_NE(strict.out.find("error: --strict"), std::string::npos) << strict.out;
  EXPECT_TRUE(fs::is_regular_file(dir / "r.json")) << "the report is written all the same";
}

TEST(RunWarnings, ASolverStoppedAboveItsToleranceNamesTheFirstStepAndFailsUnderStrict) {
  const fs::path dir = out_dir("warn_solver");
  const fs::path scene = bead_scene(dir, kEndBox, kCapped);
  const CliResult r = run_serosa("headless " + shell_quote(scene.string()) + " --report " +
                                 shell_quote((dir / "r.json").string()) + " --strict");
  EXPECT_EQ(r.code, 4) << r.out;
  EXPECT_NE(r.out.find("warning: the solver stopped above its tolerance on 40 of 40 steps, first "
                       "on step 0 at 0 s"),
            std::string::npos)
      << r.out;
  EXPECT_NE(r.out.find("after 2 iterations against a tolerance of 1e-09 and a cap of 2"),
            std::string::npos)
      << r.out;
  const nlohmann::json j = read_report(dir / "r.json");
  EXPECT_GT(j["fixed"]["nodes"].get<int>(), 0) << j["fixed"].dump();
  EXPECT_EQ(j["fixed"]["organs"][0]["box"], j["fixed"]["nodes"]);
  bool said = false;
  for (const auto& w : j["warnings"]) said = said || w["kind"] == "not_converged";
  EXPECT_TRUE(said) << j["warnings"].dump(1);
}

TEST(RunWarnings, ASoundRunIsSilentEvenUnderStrict) {
  const fs::path dir = out_dir("warn_none");
  const fs::path scene = bead_scene(dir, kEndBox, kSound);
  const CliResult r = run_serosa("headless " + shell_quote(scene.string()) + " --report " +
                                 shell_quote((dir / "r.json").string()) + " --strict");
  EXPECT_EQ(r.code, 0) << r.out;
  EXPECT_EQ(r.out.find("warning:"), std::string::npos) << r.out;
  EXPECT_TRUE(read_report(dir / "r.json")["warnings"].empty());
}

}  // namespace
}  // namespace serosa::app
