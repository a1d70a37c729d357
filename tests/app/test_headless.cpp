// serosa headless end to end: the bundled scenes run, the report is honest, outputs round trip.
#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <random>

#include <spdlog/sinks/ringbuffer_sink.h>
#include <spdlog/spdlog.h>

#include "app/headless.h"
#include "engine/input_error.h"
#include "engine/io/mesh_io.h"
#include "engine/sim_state.h"
#include "support/test_paths.h"

namespace serosa::app {
namespace {

namespace fs = std::filesystem;

fs::path out_dir(const std::string& name) {
  const fs::path d = fs::path(::serosa::test_paths::binary_dir()) / "test-output" / "app" / name;
  fs::remove_all(d);
  fs::create_directories(d);
  return d;
}

TEST(Headless, BeamSceneRunsAndReportsWhatItSimulated) {
  const fs::path dir = out_dir("beam");
  HeadlessOptions o;
  o.scene = fs::path(::serosa::test_paths::source_dir()) / "config" / "beam.toml";
  o.steps = 20;
  o.report = dir / "report.json";
  o.export_final = dir / "final.msh";
  o.progress = false;
  const auto report = run_headless(o);
  EXPECT_EQ(report["steps"], 20);
  EXPECT_TRUE(fs::exists(dir / "report.json"));
  EXPECT_EQ(report["effects"]["simulated"][0], "fem");
  EXPECT_EQ(report["fem"]["rejected"], 0);
  EXPECT_EQ(report["fem"]["energy_gains"], 0);  // converged solves only dissipate
  EXPECT_EQ(report["fem"]["energy_removed_j"], 0.0);
  // The exported mesh is the final state: same topology, deformed positions.
  const TetMesh final_mesh = read_mesh(dir / "final.msh");
  EXPECT_EQ(final_mesh.num_tets(), report["mesh_final"]["tets"].get<int>());
  EXPECT_TRUE(report["mesh_final"]["valid"].get<bool>());
}

TEST(Headless, SameInputsGiveTheSameStateHash) {
  HeadlessOptions o;
  o.scene = fs::path(::serosa::test_paths::source_dir()) / "config" / "beam.toml";
  o.steps = 10;
  o.progress = false;
  EXPECT_EQ(run_headless(o)["state_hash"], run_headless(o)["state_hash"]);
}

TEST(Headless, AppendectomyWritesPictures) {
  const fs::path dir = out_dir("appendectomy");
  HeadlessOptions o;
  o.scene = fs::path(::serosa::test_paths::source_dir()) / "config" / "appendectomy.toml";
  o.steps = 4;
  o.frames = dir / "frames";
  o.frame_count = 2;
  o.progress = false;
  const auto report = run_headless(o);
  ASSERT_EQ(report["frames"].size(), 2u);
  for (const auto& f : report["frames"]) EXPECT_GT(fs::file_size(f.get<std::string>()), 1000u);
}

// Every field of the report a regression run is judged by (docs/headless-report.md), each with a
// value that could be wrong: the scripted transection of the transection drill, pictures on.
TEST(Headless, ReportHasEveryFieldWithPlausibleValues) {
  const fs::path dir = out_dir("report_fields");
  HeadlessOptions o;
  o.scene = fs::path(::serosa::test_paths::source_dir()) / "config" / "transection.toml";
  o.tool_path = fs::path(::serosa::test_paths::source_dir()) / "config" / "paths" /
                "appendix_transection.csv";
  o.steps = 26;  // the stroke closes at step 23
  o.frames = dir / "frames";
  o.frame_count = 2;
  o.report = dir / "report.json";
  o.progress = false;
  const auto r = run_headless(o);
  // Steps, cuts, tets.
  EXPECT_EQ(r["steps"], 26);
  EXPECT_EQ(r["steps_taken"], 26);
  EXPECT_EQ(r["cutting"]["cuts"], 1);
  EXPECT_GT(r["mesh_final"]["tets"].get<int>(), r["mesh_initial"]["tets"].get<int>());
  // Time per stage: FEM, cut, surface, render (pictures), all measured.
  for (const char* stage : {"fem", "cutting", "surface", "render", "contact", "metrics"})
    EXPECT_GT(r["time_per_stage_ms"].value(stage, 0.0), 0.0) << stage;
  // State hash: 16 hex digits.
  const std::string hash = r["state_hash"];
  EXPECT_EQ(hash.size(), 16u);
  EXPECT_EQ(hash.find_first_not_of("0123456789abcdef"), std::string::npos);
  // Metrics.
  const auto& m = r["metrics"];
  EXPECT_NEAR(m["time_s"].get<double>(), 26 * 0.005, 1e-12);
  for (const char* tool : {"grasper", "scissors", "endoscope"})
    EXPECT_EQ(m["path_length_m"][tool].get<double>(), 0.0) << tool;  // all parked
  for (const char* tool : {"grasper", "endoscope"}) {
    EXPECT_EQ(m["force_max_n"][tool].get<double>(), 0.0) << tool;  // touching nothing
    EXPECT_EQ(m["force_mean_n"][tool].get<double>(), 0.0) << tool;
  }
  // The blades pushed nothing aside but sheared the appendix they closed on.
  EXPECT_GT(m["force_max_n"]["scissors"].get<double>(), 0.1);
  EXPECT_GT(m["peak_stress_pa"].get<double>(), 0.0);  // the cut tissue relaxes
  // The cut runs along the planned line (through the appendix, 7 mm across): tets cut within
  // the appendix's radius plus a tet of it; none outside the 4 mm band but a few at the rim.
  const auto& cut = m["cut"];
  EXPECT_GT(cut["volume_m3"].get<double>(), 0.0);
  EXPECT_GT(cut["deviation_mean_m"].get<double>(), 0.0);
  EXPECT_LE(cut["deviation_mean_m"].get<double>(), cut["deviation_max_m"].get<double>());
  EXPECT_LT(cut["deviation_max_m"].get<double>(), 0.0035 + 0.004);
  EXPECT_LT(cut["deviation_mean_m"].get<double>(), 0.003);
  EXPECT_LT(cut["collateral_m3"].get<double>(), 0.25 * cut["volume_m3"].get<double>());
  EXPECT_EQ(cut["band_m"].get<double>(), 0.004);
  // The step times and the real-time factor.
  const auto& st = r["step_time_ms"];
  EXPECT_GT(st["p50"].get<double>(), 0.0);
  EXPECT_LE(st["p50"].get<double>(), st["p99"].get<double>());
  EXPECT_LE(st["p99"].get<double>(), st["max"].get<double>());
  EXPECT_GT(r["real_time_factor"].get<double>(), 0.0);
  // Each of the slowest steps says how much of it was the FEM's and what its solve did.
  for (const auto& s : st["slowest"]) {
    EXPECT_LE(s["fem_ms"].get<double>(), s["ms"].get<double>());
    EXPECT_GE(s["cg_iterations"].get<int>(), 0);
  }
}

TEST(Headless, StepTimesGiveQuantilesAndTheSlowestStepsByIndex) {
  std::mt19937 rng(4);
  std::uniform_int_distribution<int> ms(1, 40);  // many ties
  for (int trial = 0; trial < 200; ++trial) {
    std::vector<double> steps(1 + static_cast<std::size_t>(trial) * 7);
    for (double& v : steps) v = 0.25 * ms(rng);
    const auto j = step_time_json(steps);
    std::vector<double> sorted = steps;
    std::sort(sorted.begin(), sorted.end());
    const auto q = [&](double f) {
      return sorted[std::min(sorted.size() - 1,
                             static_cast<std::size_t>(f * static_cast<double>(sorted.size())))];
    };
    ASSERT_EQ(j["p50"].get<double>(), q(0.5));
    ASSERT_EQ(j["p99"].get<double>(), q(0.99));
    ASSERT_EQ(j["max"].get<double>(), sorted.back());
    const auto& slow = j["slowest"];
    ASSERT_EQ(slow.size(), std::min<std::size_t>(8, steps.size()));
    for (std::size_t i = 0; i < slow.size(); ++i) {
      const auto at = slow[i]["step"].get<std::size_t>();
      ASSERT_EQ(slow[i]["ms"].get<double>(), steps[at]);
      ASSERT_EQ(steps[at], sorted[sorted.size() - 1 - i]);  // the i-th slowest
      if (i > 0 && steps[at] == slow[i - 1]["ms"].get<double>()) {
        ASSERT_GT(at, slow[i - 1]["step"].get<std::size_t>());  // ties by step
      }
    }
  }
  EXPECT_TRUE(step_time_json({})["slowest"].empty());
}

TEST(Headless, EachSlowestStepSaysWhereItsTimeWent) {
  std::mt19937 rng(8);
  std::uniform_int_distribution<int> its(0, 200);
  std::vector<double> ms(300);
  std::vector<StepDetail> details(ms.size());
  for (std::size_t i = 0; i < ms.size(); ++i) {
    ms[i] = 0.01 * static_cast<double>(i % 97) + 1.0;
    details[i] = {0.5 * ms[i], its(rng), i % 5 == 0, i % 7 == 0, 0.25 * ms[i]};
  }
  const auto j = step_time_json(ms, details);
  ASSERT_EQ(j["slowest"].size(), 8u);
  for (const auto& s : j["slowest"]) {
    const auto& d = details[s["step"].get<std::size_t>()];
    EXPECT_EQ(s["fem_ms"].get<double>(), d.fem_ms);
    EXPECT_EQ(s["cg_iterations"].get<int>(), d.cg_iterations);
    EXPECT_EQ(s["factor_refresh"].get<bool>(), d.factor_refresh);
    EXPECT_EQ(s["factor_patch"].get<bool>(), d.factor_patch);
    EXPECT_EQ(s["factor_wait_ms"].get<double>(), d.factor_wait_ms);
  }
  // Without details, steps and times only.
  EXPECT_FALSE(step_time_json(ms)["slowest"][0].contains("cg_iterations"));
}

TEST(Headless, DefaultSceneRunsWithoutAWarning) {
  // Every listed effect is simulated or handled: "record" without a file is said at info level.
  auto sink = std::make_shared<spdlog::sinks::ringbuffer_sink_mt>(64);
  sink->set_level(spdlog::level::warn);
  spdlog::default_logger()->sinks().push_back(sink);
  HeadlessOptions o;
  o.scene = fs::path(::serosa::test_paths::source_dir()) / "config" / "appendectomy.toml";
  o.steps = 5;
  o.progress = false;
  const auto r = run_headless(o);
  spdlog::default_logger()->sinks().pop_back();
  EXPECT_TRUE(sink->last_formatted().empty()) << sink->last_formatted().front();
  EXPECT_FALSE(r["effects"].contains("unavailable")) << r["effects"].dump();
}

TEST(Headless, BadSceneIsAnInputErrorNamingTheFile) {
  const fs::path dir = out_dir("bad");
  std::ofstream(dir / "bad.toml") << "[scene]\ndt = -1\n";
  HeadlessOptions o;
  o.scene = dir / "bad.toml";
  o.progress = false;
  try {
    (void)run_headless(o);
    FAIL() << "expected InputError";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("bad.toml"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace serosa::app
