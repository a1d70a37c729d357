// The endoloop (engine/endoloop.h, contact/clip_stage.h) on a cantilever beam: cinched round the
// beam it ligates the whole cross-section inside the ring, pressing it within the loop's tight
// radius; cinched round nothing it slips off; scissors never cut through it, while the same
// stroke beside it divides the beam; a piece cut free beside it does not drag it; a run restored
// with a loop in place continues bit for bit; a scene with an endoloop but without the effect is an
// error naming the tool.
#include <gtest/gtest.h>

#include <cmath>
#include <nlohmann/json.hpp>

#include "app/headless.h"
#include "app_test_util.h"
#include "beam_scene.h"
#include "engine/clip.h"
#include "engine/endoloop.h"
#include "engine/input_error.h"
#include "engine/sim_state.h"

namespace serosa::app {
namespace {

using namespace serosa::app::testing;

// Along the beam (+x), its local +x (the side the ring lies on) along -z.
const std::string kAlong = "0.7071067811865476,0,0.7071067811865476,0";

std::unique_ptr<BeamRun> beam(const fs::path& dir, const std::string& csv,
                              const std::string& extra_tools = "",
                              const std::string& effects =
                                  "\"fem\", \"surface\", \"contact\", "
                                  "\"loops\"") {
  return beam_scene(dir, "t,tool,px,py,pz,qw,qx,qy,qz,jaw\n" + csv, effects,
                    scripted_tool("loop", "endoloop") + extra_tools);
}

// The loop open round the beam at x (its ring centred on the beam's axis), cinched by t = 0.1.
std::string loop_rows(double x = 0.07, double z = 0.01) {
  const std::string at = std::to_string(x) + ",0," + std::to_string(z) + "," + kAlong;
  return "0.00,loop," + at + ",0.9\n0.05,loop," + at + ",0.9\n0.10,loop," + at +
         ",0.0\n2.00,loop," + at + ",0.0\n";
}

TEST(Endoloop, CinchedRoundTheBeamItLigatesTheCrossSectionWithinItsTightRadius) {
  const fs::path dir = out_dir("loop_cinch");
  auto run = beam(dir, loop_rows());
  SimState& s = run->assembled.state;
  run->comp.runner->run(s, 18);
  EXPECT_TRUE(s.shared.clips.empty());
  run->comp.runner->run(s, 58);  // t = 0.38: cinched at 0.1, pressed by 0.35 (kLoopSqueezeS)
  ASSERT_EQ(s.shared.clips.size(), 1u);
  const Clip& c = s.shared.clips[0];
  EXPECT_EQ(c.kind, Clip::Kind::kLoop);
  EXPECT_EQ(c.nodes, 9u);  // the 3 x 3 nodes of the beam's cross-section at x = 7 cm
  EXPECT_EQ(c.groups, std::vector<int>{1});
  EXPECT_NEAR(c.rest_centre_m.x(), 0.07, 1e-12);
  EXPECT_LT((c.axis() - Vec3::UnitX()).norm(), 1e-9);
  std::size_t inside = 0;
  for (std::int32_t n = 0; n < s.mesh.num_nodes(); ++n) {
    const auto un = static_cast<std::size_t>(n);
    if (std::abs(s.mesh.rest[un].x() - 0.07) > 1e-9) continue;
    const Vec3 l = c.frame.transpose() * (s.mesh.x[un] - c.hinge_m);
    EXPECT_LE(std::hypot(l.x(), l.y()), kLoopTightRadius + 1e-12) << "node " << n;
    EXPECT_EQ(s.mesh.fixed[un], 1);
    ++inside;
  }
  EXPECT_EQ(inside, 9u);
  for (const Vec3& x : s.mesh.x) ASSERT_TRUE(x.allFinite());
  HeadlessOptions ho;
  ho.scene = dir / "scene.toml";
  ho.steps = 40;
  ho.progress = false;
  const nlohmann::json report = run_headless(ho);
  ASSERT_EQ(report["clips"]["placed"].size(), 1u);
  EXPECT_EQ(report["clips"]["placed"][0]["kind"], "loop");
  EXPECT_EQ(report["clips"]["dropped"]["loop"], 0);
  EXPECT_EQ(report["fem"]["not_converged"], 0);
}

TEST(Endoloop, CinchedRoundNothingItSlipsOff) {
  const fs::path dir = out_dir("loop_nothing");
  auto run = beam(dir, loop_rows(0.07, 0.04));  // the ring 3 cm above the beam
  SimState& s = run->assembled.state;
  const std::vector<std::uint8_t> fixed0 = s.mesh.fixed;
  run->comp.runner->run(s, 40);
  EXPECT_TRUE(s.shared.clips.empty());
  EXPECT_EQ(contact::clips_dropped(run->assembled.state, 0), 1);
  EXPECT_EQ(s.mesh.fixed, fixed0);
}

TEST(Endoloop, ScissorsNeverCutThroughTheLoopAndBesideItDivide) {
  const std::string sc = ",scissors,";
  const auto at = [&](double x) { return std::to_string(x) + ",-0.008,0," + kBeamAcross; };
  const std::string csv = loop_rows() + "0.00" + sc + at(0.07) + ",0.9\n0.15" + sc + at(0.07) +
                          ",0.9\n0.25" + sc + at(0.07) + ",0.0\n0.30" + sc + at(0.03) +
                          ",0.0\n0.35" + sc + at(0.03) + ",0.9\n0.45" + sc + at(0.03) +
                          ",0.0\n0.60" + sc + at(0.03) + ",0.0\n";
  const fs::path dir = out_dir("loop_scissors");
  auto run = beam(dir, csv, scripted_tool("scissors", "scissors"),
                  "\"fem\", \"surface\", \"contact\", \"loops\", \"cutting\"");
  SimState& s = run->assembled.state;
  const std::int32_t tets0 = s.mesh.num_tets();
  run->comp.runner->run(s, 56);
  const CuttingStageStats& st = run->comp.cutting->stats();
  EXPECT_EQ(st.strokes, 1u);
  EXPECT_EQ(st.strokes_on_clip, 1u);
  EXPECT_EQ(s.mesh.num_tets(), tets0);
  run->comp.runner->run(s, 44);
  EXPECT_EQ(st.strokes, 2u);
  EXPECT_GE(st.cuts, 1u);
  EXPECT_GT(s.mesh.num_tets(), tets0);
}

// A hook divides the beam 4 mm beyond the loop (cinched at 7 cm) and a grasper pulls the freed
// end 2 cm away: the loop stays with the stump. (The loop's anchors on the far side of the cut
// used to go with the freed piece and drag the loop half way after it.)
TEST(Endoloop, APieceCutFreeBesideTheLoopDoesNotDragIt) {
  std::string csv = "t,tool,px,py,pz,qw,qx,qy,qz,jaw,buttons\n";
  for (std::size_t at = 0, end = 0; (end = loop_rows().find('\n', at)) != std::string::npos;
       at = end + 1)
    csv.append(loop_rows(), at, end - at).append(",0\n");
  const auto hook = [&](const char* t, double y, double z, int pedal) {
    csv.append(t).append(",hook,0.074,").append(std::to_string(y)).append(",");
    csv.append(std::to_string(z)).append(",").append(kBeamAcross).append(",0,");
    csv.append(std::to_string(pedal)).append("\n");
  };
  hook("0.00", 0.012, -0.0065, 0);  // the crook spans z + [0, 3] mm
  hook("0.40", 0.012, -0.0065, 0);
  hook("0.41", 0.012, -0.0065, 2);  // down, across under the beam and up: the whole section
  hook("0.50", -0.008, -0.0065, 2);
  hook("0.60", -0.008, 0.0035, 2);
  hook("0.70", 0.012, 0.0035, 2);
  hook("0.71", 0.012, 0.0035, 0);
  hook("1.50", 0.012, 0.0035, 0);
  const auto grasp = [&](const char* t, double x, double jaw) {
    csv.append(t).append(",grasper,").append(std::to_string(x)).append(",0.002,0,");
    csv.append(kBeamDown).append(",").append(std::to_string(jaw)).append(",0\n");
  };
  grasp("0.00", 0.095, 0.9);
  grasp("0.02", 0.095, 0.9);
  grasp("0.05", 0.095, 0.0);
  grasp("0.75", 0.095, 0.0);
  grasp("1.00", 0.115, 0.0);
  grasp("1.50", 0.115, 0.0);
  const fs::path dir = out_dir("loop_cut_beside");
  auto run = beam_scene(dir, csv, "\"fem\", \"surface\", \"contact\", \"loops\", \"cautery\"",
                        scripted_tool("loop", "endoloop") + scripted_tool("hook", "hook") +
                            scripted_tool("grasper", "grasper"));
  SimState& s = run->assembled.state;
  run->comp.runner->run(s, 146);  // t = 0.73: cinched, settled, the beam divided beside it
  ASSERT_EQ(s.shared.clips.size(), 1u);
  ASSERT_GE(run->comp.cutting->stats().cuts, 1u);
  const Vec3 loop0 = s.shared.clips[0].hinge_m;
  const std::vector<Vec3> x0 = s.mesh.x;
  const auto moved = [&](double rest_x) {  // the largest motion of the nodes at rest_x since
    double most = 0.0;
    for (std::size_t n = 0; n < x0.size(); ++n)
      if (std::abs(s.mesh.rest[n].x() - rest_x) < 1e-9)
        most = std::max(most, (s.mesh.x[n] - x0[n]).norm());
    return most;
  };
  run->comp.runner->run(s, 74);    // t = 1.1: the end pulled 2 cm away
  EXPECT_GT(moved(0.1), 0.015);    // the freed end went with the grasper
  EXPECT_LT(moved(0.065), 0.001);  // the stump stayed
  EXPECT_LT((s.shared.clips[0].hinge_m - loop0).norm(), 0.001);
  for (const Vec3& x : s.mesh.x) ASSERT_TRUE(x.allFinite());
}

TEST(Endoloop, ARestoredSnapshotWithALoopContinuesBitForBit) {
  const fs::path dir = out_dir("loop_snapshot");
  auto run = beam(dir, loop_rows());
  SimState& s = run->assembled.state;
  run->comp.runner->run(s, 30);
  const std::vector<std::uint8_t> bytes = run->comp.runner->snapshot(s);
  auto other = restored(*run, bytes, "loop snapshot");
  SimState& o = other->assembled.state;
  ASSERT_EQ(o.shared.clips.size(), 1u);
  EXPECT_EQ(o.shared.clips[0].kind, Clip::Kind::kLoop);
  for (int k = 0; k < 40; ++k) {
    run->comp.runner->step(s);
    other->comp.runner->step(o);
    ASSERT_EQ(state_hash(o), state_hash(s)) << "step " << s.step;
  }
  EXPECT_EQ(other->comp.runner->snapshot(o), run->comp.runner->snapshot(s));
}

TEST(Endoloop, WithoutTheLoopsEffectTheSceneIsAnErrorAtTheToolsKind) {
  const fs::path dir = out_dir("loop_no_effect");
  try {
    (void)beam(dir, loop_rows(), "", "\"fem\", \"surface\", \"contact\"");
    FAIL() << "loaded";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("tool[0].kind"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("\"loops\""), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace serosa::app
