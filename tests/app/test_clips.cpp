// The clip applier and its clips (contact/clip_stage.h) on a cantilever beam: a clip closes on
// the tissue between the jaws and presses it to the clip's gap; it holds under traction, carried
// by the tissue as the grasper lifts it; a rigid motion of the tissue carries it exactly; a clip
// closed on nothing falls away; scissors closing across a clip cut nothing while the same stroke
// beside it divides the beam; a run restored from a snapshot with a clip in place continues bit
// for bit.
#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <fstream>
#include <nlohmann/json.hpp>
#include <random>

#include "app/assemble_state.h"
#include "app/compose.h"
#include "app/headless.h"
#include "app/render_frame_from_surface.h"
#include "app_test_util.h"
#include "beam_scene.h"
#include "engine/clip.h"
#include "engine/sim_state.h"

namespace serosa::app {
namespace {

using namespace serosa::app::testing;

const std::string kAcross = kBeamAcross;
const std::string kDown = kBeamDown;

// The beam with a clip applier and `extra_tools`.
std::unique_ptr<BeamRun> beam(const fs::path& dir, const std::string& csv,
                              const std::string& extra_tools = "",
                              const std::string& effects =
                                  "\"fem\", \"surface\", \"contact\", "
                                  "\"clips\"") {
  return beam_scene(dir, "t,tool,px,py,pz,qw,qx,qy,qz,jaw\n" + csv, effects,
                    scripted_tool("clipper", "clip-applier") + extra_tools);
}

// The applier over the beam at x = 7 cm, jaw tips 9 mm into it: open, then closed by t = 0.10.
std::string applier_rows(double x = 0.07) {
  const std::string at = std::to_string(x) + ",-0.004,0," + kAcross;
  return "0.00,clipper," + at + ",0.9\n0.05,clipper," + at + ",0.9\n0.10,clipper," + at +
         ",0.0\n2.00,clipper," + at + ",0.0\n";
}

// Where clamped node p is in the clip's frame (across, pin, along), m.
Vec3 in_clip(const Clip& c, const Vec3& p) { return c.frame.transpose() * (p - c.hinge_m); }

TEST(Clip, ClosesOnTheTissueBetweenTheJawsAndPressesItToTheGap) {
  const fs::path dir = out_dir("clip_closes");
  auto run = beam(dir, applier_rows());
  SimState& s = run->assembled.state;
  run->comp.runner->run(s, 18);  // t = 0.09: still opening-wide enough to be closing
  EXPECT_TRUE(s.shared.clips.empty());
  run->comp.runner->run(s, 22);  // t = 0.2: closed at 0.1, pressed by 0.15
  ASSERT_EQ(s.shared.clips.size(), 1u);
  const Clip& c = s.shared.clips[0];
  EXPECT_EQ(c.tool, 0u);
  EXPECT_NEAR(c.placed_s, 0.095, 0.006);
  // The beam's nodes at x = 7 cm in the jaws: y = 5 mm (z = 0) and y = 0 (z = -5, 0, 5 mm).
  EXPECT_EQ(c.nodes, 4u);
  EXPECT_EQ(c.groups, std::vector<int>{1});
  std::size_t pressed = 0;
  for (std::int32_t n = 0; n < s.mesh.num_nodes(); ++n) {
    const Vec3 l = in_clip(c, s.mesh.x[static_cast<std::size_t>(n)]);
    if (l.z() < kClipStart || l.z() > kClipStart + kClipLength || std::abs(l.y()) > 1e-4) continue;
    if (std::abs(l.x()) > 0.5 * kClipGap + 1e-12) continue;
    ++pressed;
    EXPECT_EQ(s.mesh.fixed[static_cast<std::size_t>(n)], 1);
  }
  EXPECT_EQ(pressed, 4u);
  for (const Vec3& x : s.mesh.x) ASSERT_TRUE(x.allFinite());
  // The report lists it by tool, time and group name.
  HeadlessOptions ho;
  ho.scene = dir / "scene.toml";
  ho.steps = 40;
  ho.progress = false;
  const nlohmann::json report = run_headless(ho);
  ASSERT_EQ(report["clips"]["placed"].size(), 1u);
  EXPECT_EQ(report["clips"]["placed"][0]["tool"], "clipper");
  EXPECT_EQ(report["clips"]["placed"][0]["groups"], nlohmann::json::array({"artery"}));
  EXPECT_EQ(report["clips"]["dropped"]["clipper"], 0);
  EXPECT_EQ(report["fem"]["not_converged"], 0);
}

TEST(Clip, HoldsUnderTractionCarriedByTheTissue) {
  // Clip at 7 cm (closed by 0.1 s, settled at 0.2 s); the grasper takes the beam's end at 9.5 cm
  // (0.05 s) and lifts it 1 cm between 0.3 and 0.5 s.
  const std::string g = "grasper,0.095,";
  const std::string csv = applier_rows() + "0.00," + g + "0.002,0," + kDown + ",0.9\n0.02," + g +
                          "0.002,0," + kDown + ",0.9\n0.05," + g + "0.002,0," + kDown +
                          ",0.0\n0.30," + g + "0.002,0," + kDown + ",0.0\n0.50," + g + "0.012,0," +
                          kDown + ",0.0\n1.00," + g + "0.012,0," + kDown + ",0.0\n";
  const fs::path dir = out_dir("clip_traction");
  auto run = beam(dir, csv, scripted_tool("grasper", "grasper"));
  SimState& s = run->assembled.state;
  run->comp.runner->run(s, 50);  // t = 0.25: settled
  ASSERT_EQ(s.shared.clips.size(), 1u);
  const Clip before = s.shared.clips[0];
  std::vector<std::int32_t> clamped;
  for (std::int32_t n = 0; n < s.mesh.num_nodes(); ++n) {
    const Vec3 l = in_clip(before, s.mesh.x[static_cast<std::size_t>(n)]);
    if (l.z() >= kClipStart && l.z() <= kClipStart + kClipLength && std::abs(l.y()) < 1e-4 &&
        std::abs(l.x()) <= 0.5 * kClipGap + 1e-12)
      clamped.push_back(n);
  }
  ASSERT_EQ(clamped.size(), 4u);
  // The tissue around the clip: the nodes at x = 6.5 and 7.5 cm.
  const auto ring_centre = [&] {
    Vec3 sum = Vec3::Zero();
    int k = 0;
    for (std::size_t n = 0; n < s.mesh.rest.size(); ++n)
      if (std::abs(std::abs(s.mesh.rest[n].x() - 0.07) - 0.005) < 1e-9) {
        sum += s.mesh.x[n];
        ++k;
      }
    return Vec3(sum / k);
  };
  const Vec3 ring0 = ring_centre();
  const Vec3 centre0 = 0.5 * (before.end(0) + before.end(1));
  run->comp.runner->run(s, 100);  // t = 0.75: lifted and held
  ASSERT_EQ(s.shared.clips.size(), 1u);
  const Clip& after = s.shared.clips[0];
  const Vec3 moved = 0.5 * (after.end(0) + after.end(1)) - centre0;
  const Vec3 ring_moved = ring_centre() - ring0;
  EXPECT_GT(ring_moved.y(), 0.002);  // the lift reached the clip's place
  EXPECT_LT((moved - ring_moved).norm(), 0.25 * ring_moved.norm()) << moved.transpose();
  // Still clamped: the same nodes, pressed to the gap, in the clip's frame as it is now.
  for (std::int32_t n : clamped) {
    const Vec3 l = in_clip(after, s.mesh.x[static_cast<std::size_t>(n)]);
    EXPECT_LE(std::abs(l.x()), 0.5 * kClipGap + 1e-9);
    EXPECT_EQ(s.mesh.fixed[static_cast<std::size_t>(n)], 1);
  }
  EXPECT_NEAR(after.frame.determinant(), 1.0, 1e-9);
  EXPECT_LT((after.frame.transpose() * after.frame - Mat3::Identity()).norm(), 1e-9);
  for (const Vec3& x : s.mesh.x) ASSERT_TRUE(x.allFinite());
}

TEST(Clip, ARigidMotionOfTheTissueCarriesTheClipExactly) {
  const fs::path dir = out_dir("clip_rigid");
  auto run = beam(dir, applier_rows());
  SimState& s = run->assembled.state;
  run->comp.runner->run(s, 50);  // settled
  ASSERT_EQ(s.shared.clips.size(), 1u);
  // The clip where the tissue as it is now puts it (the hand-off holds where it put it before
  // this step's FEM moved it).
  const StepContext ctx{s.step, s.time_s, 0.005};
  SimState still = s;
  run->comp.clips->step(ctx, still);
  std::mt19937 rng(5);
  std::normal_distribution<double> n(0.0, 1.0);
  for (int trial = 0; trial < 50; ++trial) {
    SimState moved = s;
    Eigen::Quaterniond q(n(rng), n(rng), n(rng), n(rng));
    q.normalize();
    const Mat3 r = q.toRotationMatrix();
    const Vec3 t(0.01 * n(rng), 0.01 * n(rng), 0.01 * n(rng));
    for (Vec3& x : moved.mesh.x) x = r * x + t;
    run->comp.clips->step(ctx, moved);
    const Clip& c0 = still.shared.clips[0];
    const Clip& c1 = moved.shared.clips[0];
    ASSERT_LT((c1.frame - r * c0.frame).norm(), 1e-9) << "trial " << trial;
    ASSERT_LT((c1.hinge_m - (r * c0.hinge_m + t)).norm(), 1e-11) << "trial " << trial;
    for (std::size_t k = 0; k < s.mesh.x.size(); ++k)
      ASSERT_LT((moved.mesh.x[k] - (r * still.mesh.x[k] + t)).norm(), 1e-11) << "node " << k;
  }
}

TEST(Clip, ClosedOnNothingItFallsAway) {
  const fs::path dir = out_dir("clip_nothing");
  // The applier closes 2 cm above the beam.
  std::string csv = applier_rows();
  for (std::size_t at = csv.find("-0.004"); at != std::string::npos; at = csv.find("-0.004"))
    csv.replace(at, 6, "0.030");
  auto run = beam(dir, csv);
  SimState& s = run->assembled.state;
  const std::vector<std::uint8_t> fixed0 = s.mesh.fixed;
  run->comp.runner->run(s, 40);
  EXPECT_TRUE(s.shared.clips.empty());
  EXPECT_EQ(contact::clips_dropped(run->assembled.state, 0), 1);
  EXPECT_EQ(s.mesh.fixed, fixed0);
}

TEST(Clip, ScissorsClosingOnAClipCutNothingAndBesideItDivide) {
  // The clip at 7 cm (by 0.1 s); scissors in the same plane close on it (0.15-0.25 s), then the
  // same stroke at 3 cm (0.35-0.45 s).
  const std::string sc = ",scissors,";
  const auto at = [&](double x) { return std::to_string(x) + ",-0.008,0," + kAcross; };
  const std::string csv = applier_rows() + "0.00" + sc + at(0.07) + ",0.9\n0.15" + sc + at(0.07) +
                          ",0.9\n0.25" + sc + at(0.07) + ",0.0\n0.30" + sc + at(0.03) +
                          ",0.0\n0.35" + sc + at(0.03) + ",0.9\n0.45" + sc + at(0.03) +
                          ",0.0\n0.60" + sc + at(0.03) + ",0.0\n";
  const fs::path dir = out_dir("clip_scissors");
  auto run = beam(dir, csv, scripted_tool("scissors", "scissors"),
                  "\"fem\", \"surface\", \"contact\", \"clips\", \"cutting\"");
  SimState& s = run->assembled.state;
  const std::int32_t tets0 = s.mesh.num_tets();
  run->comp.runner->run(s, 56);  // t = 0.28: the first stroke ended on the clip
  const CuttingStageStats& st = run->comp.cutting->stats();
  EXPECT_EQ(st.strokes, 1u);
  EXPECT_EQ(st.strokes_on_clip, 1u);
  EXPECT_EQ(st.cuts, 0u);
  EXPECT_EQ(s.mesh.num_tets(), tets0);
  ASSERT_EQ(st.stroke_reports.size(), 1u);
  EXPECT_TRUE(st.stroke_reports[0].on_clip);
  run->comp.runner->run(s, 44);  // t = 0.5: the second stroke cut the beam at 3 cm
  EXPECT_EQ(st.strokes, 2u);
  EXPECT_EQ(st.strokes_on_clip, 1u);
  EXPECT_GE(st.cuts, 1u);
  EXPECT_GT(s.mesh.num_tets(), tets0);
  ASSERT_EQ(s.shared.clips.size(), 1u);
}

TEST(Clip, ARestoredSnapshotWithAClipContinuesBitForBit) {
  const fs::path dir = out_dir("clip_snapshot");
  auto run = beam(dir, applier_rows());
  SimState& s = run->assembled.state;
  run->comp.runner->run(s, 30);  // pressing
  const std::vector<std::uint8_t> bytes = run->comp.runner->snapshot(s);
  auto other = restored(*run, bytes, "clip snapshot");
  SimState& o = other->assembled.state;
  ASSERT_EQ(o.shared.clips.size(), 1u);
  for (int k = 0; k < 40; ++k) {  // through the settling and on
    run->comp.runner->step(s);
    other->comp.runner->step(o);
    ASSERT_EQ(state_hash(o), state_hash(s)) << "step " << s.step;
  }
  EXPECT_EQ(other->comp.runner->snapshot(o), run->comp.runner->snapshot(s));
}

}  // namespace
}  // namespace serosa::app

namespace serosa::app {
namespace {

// The clip task marks where the clip goes: a pin through the tissue at [metrics] clip_target,
// along the posterior wall's normal, drawn as the guide (there is no planned cut to draw).
TEST(Clip, TheClipTasksTargetIsMarkedInTheView) {
  const Scene scene = load_scene(testing::source("config/clip_application.toml"));
  ASSERT_TRUE(scene.metrics.clip_target_m.has_value());
  const AssembledScene a = assemble_state(scene);
  render::RenderFrame frame;
  fill_render_tools(scene, a.state, frame);
  ASSERT_EQ(frame.guide.size(), 2u);
  const Vec3 t = *scene.metrics.clip_target_m, n = scene.supports.front().normal;
  for (int k = 0; k < 2; ++k) {
    const Vec3 p(frame.guide[k][0], frame.guide[k][1], frame.guide[k][2]);
    EXPECT_LT((p - t).cross(n).norm(), 1e-6);  // on the normal through the target
    EXPECT_NEAR((p - t).norm(), 0.004, 1e-6);
  }
}

}  // namespace
}  // namespace serosa::app
