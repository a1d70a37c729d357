// The report says what the scene's preset chose from the measured curves and what it costs and
// delivers, and the run uses those settings unless the scene overrides them.
#include <gtest/gtest.h>

#include <fstream>
#include <string>

#include "app/headless.h"
#include "app_test_util.h"
#include "engine/scene/presets.h"

namespace serosa::app {
namespace {

namespace fs = std::filesystem;
using testing::out_dir;
using testing::source;

// The validation beam with a [scene] block of our own and no [solver] table unless given.
fs::path beam_scene(const fs::path& dir, const std::string& scene_keys, const std::string& extra) {
  const fs::path file = dir / "beam.toml";
  std::ofstream os(file);
  os << "[scene]\ndt = 0.01\neffects = [\"fem\", \"gravity\"]\n"
     << scene_keys << "\n"
     << "[[organ]]\nname = \"beam\"\nmesh = \"" << source("assets/beam_coarse.msh").string()
     << "\"\nyoung = 5.0e6\npoisson = 0.3\ndensity = 1.0e3\n"
     << "fixed = { box = [[-0.001, -0.01, -0.01], [0.0001, 0.01, 0.01]] }\n"
     << extra;
  return file;
}

nlohmann::json run(const fs::path& scene) {
  HeadlessOptions o;
  o.scene = scene;
  o.steps = 3;
  o.progress = false;
  return run_headless(o);
}

TEST(PresetReport, EachQualityReportsItsMeasuredCostAndError) {
  double prev_ms = 0.0;
  double prev_error = 1.0;
  for (const char* q : {"fast", "balanced", "accurate"}) {
    const fs::path dir = out_dir(std::string("preset_") + q);
    const auto r = run(beam_scene(dir, std::string("quality = \"") + q + "\"", ""));
    ASSERT_TRUE(r.contains("preset")) << q;
    const auto& p = r["preset"];
    EXPECT_EQ(p["quality"], q);
    EXPECT_TRUE(p["target_met"].get<bool>()) << q;
    EXPECT_LE(p["solver"]["measured_rel_error"].get<double>(), p["target_rel_error"].get<double>());
    EXPECT_FALSE(p["solver"]["overridden"].get<bool>());
    // The run used what the preset chose.
    EXPECT_EQ(r["solver"]["max_iterations"], p["solver"]["max_iterations"]) << q;
    EXPECT_EQ(r["solver"]["kind"], p["solver"]["kind"]) << q;
    // Better presets cost more and deliver more.
    const double ms = p["solver"]["measured_ms_per_step"].get<double>();
    const double err = p["solver"]["measured_rel_error"].get<double>();
    EXPECT_GE(ms, prev_ms) << q;
    EXPECT_LE(err, prev_error) << q;
    prev_ms = ms;
    prev_error = err;
    ASSERT_TRUE(p.contains("tessellation"));
    EXPECT_GE(p["tessellation"]["level"].get<int>(), 1);
  }
}

TEST(PresetReport, ExplicitSolverKeysWinAndTheReportSaysSo) {
  const fs::path dir = out_dir("preset_override");
  const auto r = run(beam_scene(dir, "accuracy_target = 0.01", "[solver]\nmax_iterations = 13\n"));
  EXPECT_EQ(r["solver"]["max_iterations"], 13);
  EXPECT_TRUE(r["preset"]["solver"]["overridden"].get<bool>());
  EXPECT_FALSE(r["preset"].contains("quality"));
  EXPECT_FALSE(r["preset"].contains("tessellation"));  // a target alone sets only the solver
}

TEST(PresetReport, NoPresetNoBlock) {
  const fs::path dir = out_dir("preset_none");
  const auto r = run(beam_scene(dir, "", ""));
  EXPECT_FALSE(r.contains("preset"));
  EXPECT_EQ(r["solver"]["max_iterations"], scene_default_solver().max_iterations);
}

}  // namespace
}  // namespace serosa::app
