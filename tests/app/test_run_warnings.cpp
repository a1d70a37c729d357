// A run that did not do what its scene asked says so (app/run_warnings.h): a solver that stops
// above its tolerance and a fixed box that selects nothing are warnings on stderr and in the
// report, naming the first step and the figures, and `--strict` turns them into exit 4 with the
// report still written; a run with neither is silent, strict or not. A tool path given in place of
// the scene's that outlasts the scene's steps is said too, with the steps that play all of it.
#include <gtest/gtest.h>

#include <fstream>
#include <sstream>
#include <string>

#include <nlohmann/json.hpp>

#include "app/run_warnings.h"
#include "app_test_util.h"
#include "engine/scene/scene.h"
#include "engine/shell_command.h"

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

// The novice's appendectomy (14.1 s) in place of the expert's (9.4 s, the scene's 1880 steps): cut
// off, and said; the expert's own length is not.
TEST(RunWarnings, APathLongerThanTheScenesStepsIsSaid) {
  const Scene scene = load_scene(source("config/appendectomy.toml"));
  const fs::path novice = source("config/paths/appendectomy_procedure_novice.csv");
  const std::vector<RunWarning> w = path_warnings(scene, novice, scene.headless.steps);
  ASSERT_EQ(w.size(), 1u);
  EXPECT_EQ(w[0].kind, "path_cut_short");
  EXPECT_EQ(w[0].text, "the scripted path " + novice.string() +
                           " lasts 14.1 s but the run stops at 9.4 s (1880 steps, the scene's "
                           "[headless] steps): --steps 2820 runs all of it");
  EXPECT_TRUE(path_warnings(scene, novice, 2820).empty());
  EXPECT_TRUE(
      path_warnings(scene, source("config/paths/appendectomy_procedure.csv"), 1880).empty());
}

// `serosa headless --path` with the scene's steps: the warning on stderr, in the report and in
// the summary's warnings line; with --steps, or a path that ends before the run, none.
TEST(RunWarnings, APathCutShortWarnsOnTheCommandLineAndAShortOneDoesNot) {
  const fs::path dir = out_dir("warn_path");
  const std::string head = "headless " + shell_quote(source("config/cut_line.toml").string()) +
                           " --set headless.steps=20 --report " +
                           shell_quote((dir / "r.json").string());
  const fs::path novice = source("config/paths/appendectomy_novice.csv");
  const CliResult cut = run_serosa(head + " --path " + shell_quote(novice.string()));
  EXPECT_EQ(cut.code, 0) << cut.out;
  const std::string text = "the scripted path " + novice.string() +
                           " lasts 12 s but the run stops at 0.1 s (20 steps, the scene's "
                           "[headless] steps): --steps 2400 runs all of it";
  EXPECT_NE(cut.out.find("warning: " + text), std::string::npos) << cut.out;
  EXPECT_NE(cut.out.find("warnings   1; the first: " + text), std::string::npos) << cut.out;
  nlohmann::json r = read_report(dir / "r.json");
  ASSERT_EQ(r["warnings"].size(), 1u) << r["warnings"].dump(1);
  EXPECT_EQ(r["warnings"][0]["kind"], "path_cut_short");

  const CliResult asked =
      run_serosa(head + " --steps 20 --path " + shell_quote(novice.string()) + " --strict");
  EXPECT_EQ(asked.code, 0) << asked.out;
  EXPECT_EQ(asked.out.find("warning:"), std::string::npos) << asked.out;

  // The first 0.05 s of the expert's path: it ends before the run's 0.1 s.
  std::ofstream shorter(dir / "short.csv");
  std::istringstream rows(file_text(source("config/paths/appendectomy.csv")));
  for (std::string line; std::getline(rows, line);)
    if (line.empty() || line[0] == '#' || line[0] == 't' || std::stod(line) <= 0.05)
      shorter << line << '\n';
  shorter.close();
  const CliResult ends =
      run_serosa(head + " --path " + shell_quote((dir / "short.csv").string()) + " --strict");
  EXPECT_EQ(ends.code, 0) << ends.out;
  EXPECT_EQ(ends.out.find("warning:"), std::string::npos) << ends.out;
  EXPECT_TRUE(read_report(dir / "r.json")["warnings"].empty());
}

}  // namespace
}  // namespace serosa::app
