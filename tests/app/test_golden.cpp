// Headless regression against a golden report: stated tolerances, a missing golden fails unless
// --update-golden, the CLI exits 3 on a mismatch.
#include <gtest/gtest.h>

#include <fstream>

#include "app_test_util.h"
#include "batch/golden.h"

namespace serosa::batch {
namespace {

using namespace serosa::app::testing;
using Json = nlohmann::json;

Json sample() {
  return Json::parse(R"({
    "steps": 10, "steps_taken": 10, "simulated_time_s": 0.05, "state_hash": "00ff",
    "mesh_final": {"tets": 100, "nodes": 40, "valid": true, "rest_volume_m3": 2.0e-6},
    "cutting": {"cuts": 3, "strokes": 3, "tets_added": 30, "degenerate_tets": 0},
    "metrics": {"time_s": 0.05, "peak_stress_pa": 1000.0,
                "path_length_m": {"scissors": 0.02},
                "cut": {"volume_m3": 1.0e-7, "deviation_max_m": 0.001}},
    "time_per_stage_ms": {"fem": 3.0},
    "assessment": {"score": 88.0, "passed": true, "domains": {"efficiency": 4}}
  })");
}

TEST(Golden, TheAssessmentsPassAndDomainsAreEqualAndItsScoreWithinHalfAPoint) {
  Json r = sample();
  r["assessment"]["score"] = 88.4;
  EXPECT_TRUE(compare_golden(r, sample()).ok());
  r["assessment"]["score"] = 88.6;
  EXPECT_FALSE(compare_golden(r, sample()).ok());
  Json p = sample();
  p["assessment"]["passed"] = false;
  EXPECT_FALSE(compare_golden(p, sample()).ok());
  Json d = sample();
  d["assessment"]["domains"]["efficiency"] = 3;
  EXPECT_FALSE(compare_golden(d, sample()).ok());
}

TEST(Golden, EqualReportsMatch) {
  const GoldenComparison c = compare_golden(sample(), sample());
  EXPECT_TRUE(c.ok());
  EXPECT_TRUE(c.notes.empty());
}

TEST(Golden, CountsMustBeEqual) {
  Json r = sample();
  r["mesh_final"]["tets"] = 101;
  const GoldenComparison c = compare_golden(r, sample());
  ASSERT_EQ(c.failures.size(), 1u);
  EXPECT_NE(c.failures[0].find("/mesh_final/tets: golden 100, got 101"), std::string::npos)
      << c.failures[0];
}

TEST(Golden, MetricsWithinToleranceMatchAndBeyondFail) {
  Json r = sample();
  r["metrics"]["peak_stress_pa"] = 1000.9;                // < 1e-3 relative (1 Pa)
  r["metrics"]["path_length_m"]["scissors"] = 0.0200005;  // within 1e-3 relative
  EXPECT_TRUE(compare_golden(r, sample()).ok());
  r["metrics"]["cut"]["deviation_max_m"] = 0.0012;
  const GoldenComparison c = compare_golden(r, sample());
  ASSERT_EQ(c.failures.size(), 1u);
  EXPECT_NE(c.failures[0].find("/metrics/cut/deviation_max_m"), std::string::npos);
  // A metric missing from the report fails too.
  Json m = sample();
  m["metrics"].erase("peak_stress_pa");
  EXPECT_FALSE(compare_golden(m, sample()).ok());
}

// The failure named largest is the one furthest beyond its tolerance, whatever its place: a
// metric ten thousand tolerances off beats one just off, and a state hash never beats either.
TEST(Golden, TheLargestMismatchIsTheOneFurthestBeyondItsTolerance) {
  Json r = sample();
  r["metrics"]["time_s"] = 0.05 * (1.0 + 2e-3);  // twice its 1e-3 relative tolerance
  r["metrics"]["peak_stress_pa"] = 11000.0;      // 10,000 tolerances of 1 Pa
  r["metrics"]["cut"]["deviation_max_m"] = 0.0011;
  const GoldenComparison c = compare_golden(r, sample());
  ASSERT_EQ(c.failures.size(), 3u);
  EXPECT_NE(c.failures[c.largest].find("/metrics/peak_stress_pa: golden 1000.0, got 11000.0"),
            std::string::npos)
      << c.failures[c.largest];
  EXPECT_NEAR(c.largest_excess, 1e4, 1.0);
  Json counted = sample();
  counted["metrics"]["time_s"] = 0.06;
  counted["cutting"]["cuts"] = 4;  // no tolerance: beyond any
  const GoldenComparison k = compare_golden(counted, sample());
  ASSERT_EQ(k.failures.size(), 2u);
  EXPECT_NE(k.failures[k.largest].find("/cutting/cuts"), std::string::npos);
}

TEST(Golden, TimingsAreIgnoredAndHashIsOnlyNoted) {
  Json r = sample();
  r["time_per_stage_ms"]["fem"] = 300.0;
  r["state_hash"] = "0100";
  const GoldenComparison c = compare_golden(r, sample());
  EXPECT_TRUE(c.ok());
  EXPECT_EQ(c.notes.size(), 1u);
}

// Final node positions: each within kGoldenPositionTolerance, and the mismatch names how many
// are beyond it and the farthest node with both positions.
TEST(Golden, NodePositionsWithinTheToleranceMatchAndTheFarthestIsNamed) {
  Json g = sample();
  g["nodes_final_m"] = Json::array();
  for (int i = 0; i < 40; ++i) g["nodes_final_m"].push_back({0.001 * i, 0.0, 0.0});
  Json r = g;
  r["nodes_final_m"][7][1] = 0.5 * kGoldenPositionTolerance;
  EXPECT_TRUE(compare_golden(r, g).ok());
  r["nodes_final_m"][3][2] = 2.0 * kGoldenPositionTolerance;
  r["nodes_final_m"][9][0] = 0.009 + 5.0 * kGoldenPositionTolerance;
  const GoldenComparison c = compare_golden(r, g);
  ASSERT_EQ(c.failures.size(), 1u);
  EXPECT_NE(c.failures[0].find("2 of 40 nodes beyond"), std::string::npos) << c.failures[0];
  EXPECT_NE(c.failures[0].find("node 9"), std::string::npos) << c.failures[0];
  Json fewer = g;
  fewer["nodes_final_m"].erase(0);
  EXPECT_FALSE(compare_golden(fewer, g).ok());
}

// The state hash binds only when the same binary with the same thread count wrote the golden.
TEST(Golden, TheHashMustMatchForTheSameBinaryAndThreads) {
  Json g = sample();
  g["binary_id"] = "abc";
  g["solver"] = {{"threads", 1}};
  Json r = g;
  r["state_hash"] = "0f0f";
  EXPECT_FALSE(compare_golden(r, g).ok());  // the same binary, the same threads
  r["binary_id"] = "def";
  GoldenComparison c = compare_golden(r, g);
  EXPECT_TRUE(c.ok());  // another binary: noted
  EXPECT_EQ(c.notes.size(), 1u);
  r["binary_id"] = "abc";
  r["solver"]["threads"] = 2;
  EXPECT_TRUE(compare_golden(r, g).ok());  // another thread count: noted
}

// A run paced to real time (the emulated rig in the loop) is compared on what timing cannot
// change: its steps, validity, the blades' strokes, whether it passed, and volume.
TEST(Golden, ARunPacedToRealTimeComparesWhatTimingCannotChange) {
  Json g = sample();
  g["paced_to_real_time"] = true;
  Json r = g;
  r["metrics"]["peak_stress_pa"] = 5000.0;
  r["mesh_final"]["tets"] = 104;
  r["state_hash"] = "1234";
  const GoldenComparison c = compare_golden(r, g);
  EXPECT_TRUE(c.ok());
  ASSERT_EQ(c.notes.size(), 1u);
  EXPECT_NE(c.notes[0].find("paced to real time"), std::string::npos);
  r["cutting"]["cuts"] = 2;  // one stroke's sweep landing as two cuts: timing
  EXPECT_TRUE(compare_golden(r, g).ok());
  r["cutting"]["strokes"] = 2;
  EXPECT_FALSE(compare_golden(r, g).ok());
  r = g;
  r["assessment"]["passed"] = false;
  EXPECT_FALSE(compare_golden(r, g).ok());
  r = g;
  r["mesh_final"]["rest_volume_m3"] = 2.1e-6;
  EXPECT_FALSE(compare_golden(r, g).ok());
}

TEST(Golden, MissingGoldenFailsUnlessUpdating) {
  const fs::path dir = out_dir("golden_unit");
  const GoldenComparison missing = check_golden(sample(), dir / "g.json", false);
  ASSERT_FALSE(missing.ok());
  EXPECT_NE(missing.failures[0].find("missing"), std::string::npos);
  EXPECT_TRUE(check_golden(sample(), dir / "g.json", true).ok());
  EXPECT_TRUE(check_golden(sample(), dir / "g.json", false).ok());
  std::ofstream(dir / "bad.json") << "{not json";
  EXPECT_FALSE(check_golden(sample(), dir / "bad.json", false).ok());
}

TEST(Golden, CliExitsThreeOnMismatchOrMissingGolden) {
  const fs::path dir = out_dir("golden_cli");
  const std::string run = "headless '" + source("config/beam.toml").string() + "' --steps 3 ";
  const std::string golden = "--golden '" + (dir / "beam.json").string() + "'";
  EXPECT_EQ(run_serosa(run + golden).code, 3);
  const CliResult write = run_serosa(run + golden + " --update-golden");
  EXPECT_EQ(write.code, 0) << write.out;
  const CliResult same = run_serosa(run + golden);
  EXPECT_EQ(same.code, 0) << same.out;
  EXPECT_NE(same.out.find("golden matches"), std::string::npos) << same.out;
  const CliResult longer =
      run_serosa("headless '" + source("config/beam.toml").string() + "' --steps 4 " + golden);
  EXPECT_EQ(longer.code, 3) << longer.out;
  EXPECT_NE(longer.out.find("golden mismatch: /steps"), std::string::npos) << longer.out;
  // Several lines differ; the largest is said once more on its own line, for a batch's reason.
  EXPECT_NE(longer.out.find("golden mismatch, largest: /steps: golden 3, got 4"), std::string::npos)
      << longer.out;
}

}  // namespace
}  // namespace serosa::batch
