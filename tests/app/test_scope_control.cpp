// The endoscope in the trainee's hands (window/scope_control.h): it starts where the script started
// it, pivots about its trocar (the shaft always through the port), inserts along its shaft, and
// rotating it sweeps the 30 degree optic's view around the shaft; the solver takes its pose at the
// step boundary (engine/live_pose_stage.h).
#include <gtest/gtest.h>

#include <cmath>

#include "app_test_util.h"
#include "engine/live_pose_stage.h"
#include "engine/scene/tool_path.h"
#include "engine/scope_view.h"
#include "engine/sim_state.h"
#include "render/camera.h"
#include "window/scope_control.h"

namespace serosa::app {
namespace {

using namespace serosa::app::testing;

Vec3 tip_of(const ToolState& s) { return {s.tip_m[0], s.tip_m[1], s.tip_m[2]}; }
Vec3 shaft_of(const ToolState& s) {
  return Quat(s.quat_wxyz[0], s.quat_wxyz[1], s.quat_wxyz[2], s.quat_wxyz[3]).normalized() *
         Vec3::UnitZ();
}
Vec3 view_of(const ToolState& s, float scope_deg) {
  const auto f = [](const std::array<double, 3>& a) {
    return std::array<float, 3>{static_cast<float>(a[0]), static_cast<float>(a[1]),
                                static_cast<float>(a[2])};
  };
  const std::array<float, 4> q{
      static_cast<float>(s.quat_wxyz[0]), static_cast<float>(s.quat_wxyz[1]),
      static_cast<float>(s.quat_wxyz[2]), static_cast<float>(s.quat_wxyz[3])};
  const render::Camera c = render::endoscope_camera(f(s.tip_m), q, scope_deg);
  return Vec3(c.target[0] - c.eye[0], c.target[1] - c.eye[1], c.target[2] - c.eye[2]).normalized();
}

struct Scope {
  Tool tool;
  ToolState start;
};

// The default scene's endoscope at its scripted start.
Scope default_scope() {
  const Scene scene = load_scene(source("config/transection.toml"));
  for (const Tool& t : scene.tools)
    if (t.kind == ToolKind::kEndoscope)
      return {t, sample(read_tool_path(t.device.script), t.name, 0.0)};
  ADD_FAILURE() << "no endoscope";
  return {};
}

TEST(ScopeControl, StartsWhereTheScriptStartsIt) {
  const Scope s = default_scope();
  const window::ScopeControl scope(s.tool, s.start);
  const ToolState p = scope.pose().load();
  EXPECT_GT(p.tick, 0u);  // published: the solver's first step takes it
  EXPECT_LT((tip_of(p) - tip_of(s.start)).norm(), 1e-12);
  EXPECT_LT((shaft_of(p) - shaft_of(s.start)).norm(), 1e-12);
}

TEST(ScopeControl, PivotsAboutItsPortInsertsAlongItsShaftAndRotatesAboutIt) {
  const Scope s = default_scope();
  window::ScopeControl scope(s.tool, s.start);
  const Vec3 pivot = scope.trocar().pivot_m;
  const ToolState p0 = scope.pose().load();
  for (int k = 0; k < 50; ++k) {  // a walk of drags, insertions and turns
    scope.move(0.03 * std::sin(k), 0.05 * std::cos(0.7 * k), k % 3 == 0 ? 0.004 : -0.002,
               0.1 * (k % 2 ? 1 : -1));
    const ToolState p = scope.pose().load();
    const Vec3 to_tip = tip_of(p) - pivot;
    // The shaft passes through the port, and the tip lies the insertion down it.
    EXPECT_LT(to_tip.cross(shaft_of(p)).norm(), 1e-12) << k;
    EXPECT_NEAR(to_tip.dot(shaft_of(p)), scope.joints().insertion_m, 1e-12) << k;
  }
  // Insertion alone moves the tip along the shaft.
  window::ScopeControl in(s.tool, s.start);
  in.move(0.0, 0.0, 0.01, 0.0);
  const ToolState p1 = in.pose().load();
  EXPECT_LT((tip_of(p1) - tip_of(p0) - 0.01 * shaft_of(p0)).norm(), 1e-12);
  // Rotation alone keeps tip and shaft; the 0 degree view stays, the 30 degree one sweeps round.
  window::ScopeControl turn(s.tool, s.start);
  turn.move(0.0, 0.0, 0.0, 1.0);
  const ToolState p2 = turn.pose().load();
  EXPECT_LT((tip_of(p2) - tip_of(p0)).norm(), 1e-12);
  EXPECT_LT((shaft_of(p2) - shaft_of(p0)).norm(), 1e-12);
  EXPECT_LT((view_of(p2, 0.0f) - view_of(p0, 0.0f)).norm(), 1e-5);
  const Vec3 before = view_of(p0, 30.0f), after = view_of(p2, 30.0f);
  EXPECT_GT((after - before).norm(), 0.2);  // 1 rad round a 30 degree cone: 0.48
  EXPECT_NEAR(after.dot(shaft_of(p0)), std::cos(M_PI / 6), 1e-5);  // still 30 degrees off
}

// O swaps the optic: the published pose carries it, and the metrics' view of that pose
// (engine/scope_view.h) looks where the window's camera does, for either optic, wherever the
// scope is turned.
TEST(ScopeControl, TheOpticIsPartOfThePoseAndTheMetricsSeeWhatTheWindowShows) {
  const Scope s = default_scope();
  window::ScopeControl scope(s.tool, s.start);
  EXPECT_EQ(scope.pose().load().buttons & kScopeAngledButton, 0u);
  for (int k = 0; k < 200; ++k) {
    if (k % 3 == 0) scope.toggle_optic();
    scope.move(0.02 * std::sin(k), 0.03 * std::cos(0.7 * k), 0.0, 0.3);
    const ToolState p = scope.pose().load();
    const bool angled = (p.buttons & kScopeAngledButton) != 0;
    EXPECT_EQ(scope_angle_deg(p), angled ? kScopeAngleDeg : 0.0);
    const Vec3 window = view_of(p, static_cast<float>(scope_angle_deg(p)));
    EXPECT_LT((scope_view(p).dir - window).norm(), 1e-5) << k;
  }
}

TEST(LivePoseStage, TheSolverTakesTheNewestPoseAtTheStepBoundary) {
  Seqlock<ToolState> channel;
  SimState state;
  state.tools.resize(2);
  state.tools[1].tip_m = {1.0, 2.0, 3.0};
  LivePoseStage stage({{1, &channel}});
  stage.step(StepContext{0, 0.0, 0.005}, state);
  EXPECT_EQ(state.tools[1].tip_m, (std::array<double, 3>{1.0, 2.0, 3.0}));  // nothing written yet
  ToolState t;
  t.tick = 1;
  t.tip_m = {0.1, 0.2, 0.3};
  channel.store(t);
  t.tick = 2;
  t.tip_m = {0.4, 0.5, 0.6};
  channel.store(t);
  stage.step(StepContext{1, 0.005, 0.005}, state);
  EXPECT_EQ(state.tools[1].tip_m, (std::array<double, 3>{0.4, 0.5, 0.6}));
  EXPECT_EQ(state.tools[0].tip_m, (std::array<double, 3>{0.0, 0.0, 0.0}));
}

}  // namespace
}  // namespace serosa::app
