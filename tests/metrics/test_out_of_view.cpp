// Instruments out of the endoscope's view (metrics/metrics_stage.h out_of_view_s, the view of
// engine/scope_view.h): a tip placed at a known angle off the optic's axis counts as out exactly
// when that angle exceeds half the field, for the 0 and the 30 degree optic, over random scope
// poses; only posed instruments and a posed endoscope count; a restored stage goes on as the
// uninterrupted one.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <random>

#include "engine/scope_view.h"
#include "engine/sim_state.h"
#include "metrics/metrics_stage.h"
#include "support/block_copy.h"

namespace serosa::metrics {
namespace {

constexpr double kDt = 0.005;

Scene scope_and_grasper() {
  Scene scene;
  Tool scope;
  scope.name = "endoscope";
  scope.kind = ToolKind::kEndoscope;
  Tool grasper;
  grasper.name = "grasper";
  grasper.kind = ToolKind::kGrasper;
  scene.tools = {scope, grasper};
  return scene;
}

ToolState pose(const Vec3& tip, const Quat& q, std::uint32_t buttons = 0) {
  ToolState t;
  t.tip_m = {tip.x(), tip.y(), tip.z()};
  const Quat n = q.normalized();
  t.quat_wxyz = {n.w(), n.x(), n.y(), n.z()};
  t.buttons = buttons;
  return t;
}

Quat random_rotation(std::mt19937& rng) {
  std::normal_distribution<double> g(0.0, 1.0);
  return Quat(g(rng), g(rng), g(rng), g(rng)).normalized();
}

// A point at `off_rad` from the view's axis, in the direction `turn` about it, 5 cm away.
Vec3 at_angle(const ScopeView& v, double off_rad, double turn) {
  const Vec3 side = v.dir.cross(v.up);
  const Vec3 across = std::cos(turn) * v.up + std::sin(turn) * side;
  return v.eye + 0.05 * (std::cos(off_rad) * v.dir + std::sin(off_rad) * across);
}

TEST(OutOfView, ATipCountsAsOutExactlyBeyondHalfTheFieldForEitherOptic) {
  std::mt19937 rng(17);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  const double half = 0.5 * kScopeFovDeg * std::numbers::pi / 180.0;
  const LameTable table;
  for (int trial = 0; trial < 2000; ++trial) {
    const std::uint32_t optic = trial % 2 == 0 ? 0u : kScopeAngledButton;
    const ToolState scope = pose(Vec3(u(rng), u(rng), u(rng)) * 0.1, random_rotation(rng), optic);
    const ScopeView v = scope_view(scope);
    // The angled optic looks 30 degrees off the shaft, its picture's up perpendicular to it.
    const Vec3 shaft =
        Quat(scope.quat_wxyz[0], scope.quat_wxyz[1], scope.quat_wxyz[2], scope.quat_wxyz[3]) *
        Vec3::UnitZ();
    ASSERT_NEAR(std::acos(std::clamp(v.dir.dot(shaft), -1.0, 1.0)) * 180.0 / std::numbers::pi,
                scope_angle_deg(scope), 1e-5);  // acos near 1 keeps few digits
    ASSERT_NEAR(v.dir.dot(v.up), 0.0, 1e-12);
    // Clear of the field's edge by 1e-6 rad either way.
    double off = u(rng) * 1.4;
    if (std::abs(off - half) < 1e-6) off = half + 2e-6;
    const bool out = off > half;
    SimState s;
    s.tools = {scope, pose(at_angle(v, off, 2.0 * std::numbers::pi * u(rng)), Quat::Identity())};
    MetricsStage m(scope_and_grasper(), table);
    for (std::uint64_t k = 0; k < 4; ++k) m.step({k, k * kDt, kDt}, s);
    ASSERT_EQ(m.out_of_view_s(1), out ? 4 * kDt : 0.0) << "trial " << trial << " off " << off;
    ASSERT_EQ(m.out_of_view_s(0), 0.0);  // the endoscope is not an instrument in view
  }
}

TEST(OutOfView, OnlyPosedInstrumentsUnderAPosedScopeCount) {
  const LameTable table;
  const ToolState scope = pose(Vec3(0, 0, 0.1), Quat(0, 1, 0, 0));  // looking down -z
  const ToolState behind = pose(Vec3(0, 0, 0.2), Quat::Identity());
  SimState s;
  s.tools = {ToolState{}, behind};  // the scope not posed yet: nothing is judged
  MetricsStage m(scope_and_grasper(), table);
  m.step({0, 0.0, kDt}, s);
  EXPECT_EQ(m.out_of_view_s(1), 0.0);
  s.tools = {scope, ToolState{}};  // the grasper not posed yet: not in the scene
  m.step({1, kDt, kDt}, s);
  EXPECT_EQ(m.out_of_view_s(1), 0.0);
  s.tools = {scope, behind};
  m.step({2, 2 * kDt, kDt}, s);
  EXPECT_EQ(m.out_of_view_s(1), kDt);
  EXPECT_TRUE(m.report().contains("out_of_view_s"));
  // No endoscope in the scene: no such value.
  Scene alone = scope_and_grasper();
  alone.tools.erase(alone.tools.begin());
  MetricsStage none(alone, table);
  SimState one;
  one.tools = {behind};
  none.step({0, 0.0, kDt}, one);
  EXPECT_FALSE(none.report().contains("out_of_view_s"));
}

TEST(OutOfView, ARestoredStageGoesOnAsTheUninterruptedOne) {
  const LameTable table;
  const ToolState scope = pose(Vec3(0, 0, 0.1), Quat(0, 1, 0, 0));
  SimState s;
  MetricsStage whole(scope_and_grasper(), table);
  MetricsStage first(scope_and_grasper(), table);
  const auto at = [&](std::uint64_t k) {
    s.tools = {scope, pose(Vec3(0.002 * static_cast<double>(k), 0, 0.05), Quat::Identity())};
  };
  SimState cut_short;  // the run stopped at 10 steps
  for (std::uint64_t k = 0; k < 20; ++k) {
    at(k);
    whole.step({k, k * kDt, kDt}, s);
    cut_short.tools = s.tools;
    if (k < 10) first.step({k, k * kDt, kDt}, cut_short);
  }
  SimState r;
  r.blocks.metrics = test_blocks::copy(cut_short.blocks.metrics);
  MetricsStage restored(scope_and_grasper(), table);
  restored.adopt(r);
  for (std::uint64_t k = 10; k < 20; ++k) {
    at(k);
    r.tools = s.tools;
    restored.step({k, k * kDt, kDt}, r);
  }
  EXPECT_GT(whole.out_of_view_s(1), 0.0);  // it left the field part way
  EXPECT_EQ(restored.out_of_view_s(1), whole.out_of_view_s(1));
}

// View targets: a target within kTargetConeDeg of the view's axis and kTargetRange of the scope
// counts as centred at the end of that step; off the cone or too far it does not; the time is
// when the last one was first centred, and the run's time while any is missed.
TEST(ViewTargets, CentredWithinTheConeAndRangeAtTheStepTheyWere) {
  const LameTable table;
  const ToolState scope = pose(Vec3(0, 0, 0.1), Quat(0, 1, 0, 0));  // looking down -z from 10 cm
  const ScopeView v = scope_view(scope);
  const double cone = kTargetConeDeg * std::numbers::pi / 180.0;
  Scene scene = scope_and_grasper();
  scene.metrics.view_targets_m = {at_angle(v, 0.9 * cone, 0.3),  // inside the cone, 5 cm away
                                  at_angle(v, 1.1 * cone, 1.0),  // just outside it
                                  Vec3(0, 0, 0.1 - 1.1 * kTargetRange)};  // on axis, too far
  MetricsStage m(scene, table);
  SimState s;
  s.tools = {ToolState{}, ToolState{}};
  m.step({0, 0.0, kDt}, s);  // the scope not posed yet: nothing is centred
  EXPECT_EQ(m.targets_missed(), 3u);
  s.tools[0] = scope;
  m.step({1, kDt, kDt}, s);
  EXPECT_EQ(m.targets_missed(), 2u);
  EXPECT_EQ(m.targets_time_s(), 2 * kDt);  // the run's time: two are missed
  // Turned onto the second: centred now; then closer in, the third too.
  const Vec3 second = scene.metrics.view_targets_m[1] - Vec3(0, 0, 0.1);
  s.tools[0] = pose(Vec3(0, 0, 0.1), Quat::FromTwoVectors(Vec3::UnitZ(), second));
  m.step({2, 2 * kDt, kDt}, s);
  EXPECT_EQ(m.targets_missed(), 1u);
  s.tools[0] = pose(Vec3(0, 0, 0.1 - 0.5 * kTargetRange), Quat(0, 1, 0, 0));
  m.step({3, 3 * kDt, kDt}, s);
  EXPECT_EQ(m.targets_missed(), 0u) << m.report().dump();
  EXPECT_EQ(m.targets_time_s(), 4 * kDt);
  EXPECT_EQ(m.report()["view_targets"]["centred"], 3);
}

}  // namespace
}  // namespace serosa::metrics
