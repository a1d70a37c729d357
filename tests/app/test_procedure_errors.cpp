// Errors the scene detects (metrics/procedure_errors.h) on the beam, whose tissue is the group
// "artery": scissors dividing it while no clip clamps it cause a bleeding event; the same cut
// after a clip secured it does not; a live hook on a protected group is one thermal injury per
// press of the pedal; a run restored from a snapshot reports the same errors; naming a group the
// organs do not have is an error at its key.
#include <gtest/gtest.h>

#include <fstream>

#include "app/headless.h"
#include "app/render_frame_from_surface.h"
#include "app_test_util.h"
#include "beam_scene.h"
#include "engine/hook.h"
#include "engine/input_error.h"

namespace serosa::app {
namespace {

using namespace serosa::app::testing;

const std::string kHeader = "t,tool,px,py,pz,qw,qx,qy,qz,jaw,buttons\n";
const std::string kWatch = "[metrics]\nartery = \"artery\"\nprotected = [\"artery\"]\n";

// Scissors across the beam at 3 cm closing between 0.35 and 0.45 s.
std::string scissors_rows() {
  const std::string at = ",scissors,0.03,-0.008,0," + kBeamAcross;
  return "0.00" + at + ",0.9,0\n0.35" + at + ",0.9,0\n0.45" + at + ",0.0,0\n1.00" + at + ",0.0,0\n";
}

// A clip applier closing across the beam at 7 cm by 0.1 s (or far above it).
std::string applier_rows(bool on_tissue) {
  const std::string at =
      std::string(",clipper,0.07,") + (on_tissue ? "-0.004" : "0.030") + ",0," + kBeamAcross;
  return "0.00" + at + ",0.9,0\n0.05" + at + ",0.9,0\n0.10" + at + ",0.0,0\n1.00" + at + ",0.0,0\n";
}

nlohmann::json run_metrics(const fs::path& dir, const std::string& csv, const std::string& effects,
                           const std::string& tools, int steps, const std::string& extra = "") {
  auto run = beam_scene(dir, kHeader + csv, effects, tools, kWatch + extra);
  run->comp.runner->run(run->assembled.state, static_cast<std::uint64_t>(steps));
  return run->comp.metrics->report();
}

TEST(ProcedureErrors, DividingTheArteryBleedsUnlessAClipSecuredIt) {
  const std::string effects = "\"fem\", \"surface\", \"contact\", \"clips\", \"cutting\"";
  const std::string tools =
      scripted_tool("clipper", "clip-applier") + scripted_tool("scissors", "scissors");
  for (const bool clipped : {false, true}) {
    SCOPED_TRACE(clipped ? "clipped" : "not clipped");
    const nlohmann::json m =
        run_metrics(out_dir(clipped ? "errors_clipped" : "errors_unclipped"),
                    applier_rows(clipped) + scissors_rows(), effects, tools, 110);
    ASSERT_GT(m["cut"]["tets"].get<int>(), 0);  // the scissors cut either way
    EXPECT_EQ(m["bleeding_events"], clipped ? 0 : 1);
    EXPECT_EQ(m["thermal_injuries"], 0);
    if (!clipped) {
      ASSERT_EQ(m["errors"].size(), 1u);
      EXPECT_EQ(m["errors"][0]["kind"], "bleeding");
      EXPECT_NEAR(m["errors"][0]["time_s"].get<double>(), 0.45, 0.011);
      EXPECT_NEAR(m["errors"][0]["where_m"][0].get<double>(), 0.03, 0.003);
    }
  }
}

TEST(ProcedureErrors, RemovingTheArterysTetsBleedsToo) {
  // The "remove" method adds no tets: the cut is known by the tets it took out.
  const nlohmann::json m =
      run_metrics(out_dir("errors_removal"), applier_rows(false) + scissors_rows(),
                  "\"fem\", \"surface\", \"contact\", \"clips\", \"cutting\"",
                  scripted_tool("clipper", "clip-applier") + scripted_tool("scissors", "scissors"),
                  110, "[cutting]\nmethod = \"remove\"\n");
  ASSERT_GT(m["cut"]["tets"].get<int>(), 0);
  EXPECT_EQ(m["bleeding_events"], 1);
}

// A hook at 5 cm, 1 mm above the beam, drawn 10 mm down into it; the pedal held `presses` times
// (0.06-0.10 s, then 0.12-0.16 s).
std::string hook_rows(int presses) {
  const auto row = [](const std::string& t, double y, int pedal) {
    return t + ",hook,0.05," + std::to_string(y) + ",-0.0015," + kBeamAcross + ",0," +
           std::to_string(pedal * static_cast<int>(kPedalButton)) + "\n";
  };
  return row("0.00", 0.012, 0) + row("0.05", 0.006, 0) + row("0.06", 0.006, presses > 0) +
         row("0.10", 0.002, presses > 0) + row("0.11", 0.002, 0) + row("0.12", 0.002, presses > 1) +
         row("0.16", -0.004, presses > 1) + row("0.17", -0.004, 0) + row("1.00", -0.004, 0);
}

TEST(ProcedureErrors, AHookOnProtectedTissueIsOneThermalInjuryPerPress) {
  for (int presses = 0; presses <= 2; ++presses) {
    SCOPED_TRACE(presses);
    const nlohmann::json m =
        run_metrics(out_dir("errors_hook_" + std::to_string(presses)), hook_rows(presses),
                    "\"fem\", \"surface\", \"cautery\"", scripted_tool("hook", "hook"), 50);
    EXPECT_EQ(m["thermal_injuries"], presses);
    // The hook's own cut through the artery bleeds too: nothing clamps it.
    EXPECT_EQ(m["bleeding_events"], presses);
  }
}

TEST(ProcedureErrors, ARubricScoresThemAndAnUnsecuredArteryFailsTheSession) {
  const std::string effects = "\"fem\", \"surface\", \"contact\", \"clips\", \"cutting\"";
  const std::string tools =
      scripted_tool("clipper", "clip-applier") + scripted_tool("scissors", "scissors");
  for (const bool clipped : {false, true}) {
    SCOPED_TRACE(clipped ? "clipped" : "not clipped");
    const fs::path dir = out_dir(clipped ? "errors_rubric_clipped" : "errors_rubric_unclipped");
    std::ofstream(dir / "rubric.toml")
        << "title = \"Secure, then divide\"\npass_score = 50\n[[metric]]\nname = "
           "\"bleeding_events\"\ndomain = \"tissue_handling\"\nunit = \"1\"\ngood = 0.0\n"
           "poor = 1.0\nlimit = 0.0\ncritical = true\n";
    auto run = beam_scene(dir, kHeader + applier_rows(clipped) + scissors_rows(), effects, tools,
                          kWatch + "rubric = \"rubric.toml\"\n");
    HeadlessOptions ho;
    ho.scene = dir / "scene.toml";
    ho.steps = 110;
    ho.progress = false;
    const nlohmann::json report = run_headless(ho);
    EXPECT_EQ(report["assessment"]["passed"], clipped);
    EXPECT_EQ(report["assessment"]["metrics"]["bleeding_events"]["value"], clipped ? 0.0 : 1.0);
  }
  // Scored without an artery to watch: an error naming the rubric's metric.
  const fs::path dir = out_dir("errors_rubric_no_artery");
  std::ofstream(dir / "rubric.toml")
      << "title = \"t\"\npass_score = 50\n[[metric]]\nname = \"thermal_injuries\"\ndomain = "
         "\"tissue_handling\"\ngood = 0.0\npoor = 1.0\n";
  try {
    (void)beam_scene(dir, kHeader + hook_rows(0), "\"fem\", \"surface\", \"cautery\"",
                     scripted_tool("hook", "hook"), "[metrics]\nrubric = \"rubric.toml\"\n");
    ADD_FAILURE() << "no error";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("needs protected tissue to watch"), std::string::npos)
        << e.what();
  }
}

TEST(ProcedureErrors, ARestoredRunReportsTheSameErrors) {
  const fs::path dir = out_dir("errors_snapshot");
  auto run = beam_scene(dir, kHeader + hook_rows(2), "\"fem\", \"surface\", \"cautery\"",
                        scripted_tool("hook", "hook"), kWatch);
  SimState& s = run->assembled.state;
  run->comp.runner->run(s, 20);  // after the first press
  const std::vector<std::uint8_t> bytes = run->comp.runner->snapshot(s);
  auto other = restored(*run, bytes, "errors snapshot");
  run->comp.runner->run(s, 30);
  other->comp.runner->run(other->assembled.state, 30);
  EXPECT_EQ(other->comp.metrics->report(), run->comp.metrics->report());
  EXPECT_EQ(run->comp.metrics->report()["thermal_injuries"], 2);
}

TEST(ProcedureErrors, AGroupTheOrgansDoNotNameIsAnErrorAtItsKey) {
  const fs::path dir = out_dir("errors_bad_group");
  for (const auto& [keys, path] :
       {std::pair{std::string("[metrics]\nartery = \"nerve\"\n"), std::string("metrics.artery")},
        std::pair{std::string("[metrics]\nprotected = [\"artery\", \"ureter\"]\n"),
                  std::string("metrics.protected[1]")}}) {
    try {
      (void)beam_scene(dir, kHeader + hook_rows(0), "\"fem\", \"surface\", \"cautery\"",
                       scripted_tool("hook", "hook"), keys);
      ADD_FAILURE() << "no error for " << path;
    } catch (const InputError& e) {
      const std::string what = e.what();
      EXPECT_NE(what.find(path + ": unknown group"), std::string::npos) << what;
      EXPECT_NE(what.find("one of: artery"), std::string::npos) << what;
    }
  }
}

}  // namespace
}  // namespace serosa::app

namespace serosa::app {
namespace {

using namespace serosa::app::testing;

TEST(ProcedureErrors, ABleedingIsShownInTheViewWhereTheArteryWasCutAndWells) {
  const std::string at = ",scissors,0.03,-0.008,0," + kBeamAcross;
  const std::string csv = "t,tool,px,py,pz,qw,qx,qy,qz,jaw,buttons\n0.00" + at + ",0.9,0\n0.35" +
                          at + ",0.9,0\n0.45" + at + ",0.0,0\n3.00" + at + ",0.0,0\n";
  auto run = beam_scene(out_dir("errors_bleed_view"), csv, "\"fem\", \"surface\", \"cutting\"",
                        scripted_tool("scissors", "scissors"), "[metrics]\nartery = \"artery\"\n");
  SimState& s = run->assembled.state;
  run->comp.runner->run(s, 80);  // 0.4 s: not cut yet
  EXPECT_TRUE(s.shared.bleeds.empty());
  run->comp.runner->run(s, 20);  // 0.5 s: cut
  ASSERT_EQ(s.shared.bleeds.size(), 1u);
  EXPECT_NEAR(s.shared.bleeds[0].first.x(), 0.03, 0.003);
  render::RenderFrame frame;
  fill_render_tools(run->scene, s, frame);
  ASSERT_EQ(frame.bleeds.size(), 1u);
  const float early = frame.bleeds[0].radius;
  run->comp.runner->run(s, 200);  // a second later the pool is larger
  fill_render_tools(run->scene, s, frame);
  ASSERT_EQ(frame.bleeds.size(), 1u);
  EXPECT_GT(frame.bleeds[0].radius, early);
  EXPECT_NEAR(frame.bleeds[0].at[0], 0.03f, 0.003f);
}

}  // namespace
}  // namespace serosa::app
