// The clips stage's staple lines over random staplers firing in, on and beside a jittered cube (no
// FEM: the tissue moves only as the test moves it): each fire lays one line per side of the knife
// that clamps exactly the free nodes in its band inside the wedge the jaws closed from, presses
// them across to the staple height without moving them along or along the pin, never takes a
// node held already and lays nothing on no tissue (counted dropped); jaws closed on a placed
// ligature are refused (counted, nothing laid, nothing held).
#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <cmath>
#include <random>

#include "contact/clip_stage.h"
#include "engine/sim_state.h"
#include "engine/stapler.h"
#include "support/test_meshes.h"
#include "support/tool_pose.h"

namespace serosa::contact {
namespace {

Scene stapler_scene() {
  Scene scene;
  scene.settings.effects = {Effect::kFem, Effect::kSurface, Effect::kContact, Effect::kClips,
                            Effect::kCutting};
  for (const auto& [name, kind] :
       {std::pair{"clipper", ToolKind::kClipApplier}, std::pair{"stapler", ToolKind::kStapler}}) {
    Tool t;
    t.name = name;
    t.kind = kind;
    scene.tools.push_back(t);
  }
  return scene;
}

using test_support::pose;

// The free nodes of staple line k for jaws closed from `open` (the reference, from the header's
// definition of the band).
std::vector<std::int32_t> in_line(const TetMesh& m, const ToolState& ts, double open, int k) {
  const StaplerJaws j = stapler_jaws(ts, open);
  std::vector<std::int32_t> out;
  for (std::int32_t n = 0; n < m.num_nodes(); ++n) {
    const Vec3 l = j.frame.transpose() * (m.x[static_cast<std::size_t>(n)] - j.hinge);
    const double centre = k == 0 ? -kStapleLineOffset : kStapleLineOffset;
    if (l.z() >= kStapleStart && l.z() <= kCartridgeLength &&
        std::abs(l.y() - centre) <= kStapleLineHalfWidth &&
        std::abs(l.x()) <= l.z() * std::tan(0.5 * open) &&
        m.fixed[static_cast<std::size_t>(n)] == 0)
      out.push_back(n);
  }
  return out;
}

TEST(StapleLines, RandomFiresClampExactlyTheirBandsAndPressThemToTheStapleHeight) {
  const Scene scene = stapler_scene();
  std::mt19937 rng(2031);
  std::uniform_real_distribution<double> u(-0.01, 0.035), open(kStaplerArmRad, 0.6);
  std::normal_distribution<double> n(0.0, 1.0);
  int laid = 0, dropped = 0;
  for (int trial = 0; trial < 400; ++trial) {
    SimState s;
    s.mesh = test_meshes::kuhn_cube(6, 0.004, trial % 3 == 0 ? 0.0 : 0.3, 1 + trial);
    for (std::size_t i = 0; i < s.mesh.fixed.size(); ++i)  // the cube's bottom face held
      s.mesh.fixed[i] = s.mesh.rest[i].z() < 1e-9 ? 1 : 0;
    s.tools.resize(2);
    ClipStage stage(scene);
    Eigen::Quaterniond q(n(rng), n(rng), n(rng), n(rng));
    q.normalize();
    const Vec3 tip(u(rng), u(rng), u(rng));
    const double wide = open(rng);
    s.tools[1] = pose(tip, q, wide);
    stage.step({0, 0.0, 0.005}, s);
    ASSERT_TRUE(s.shared.clips.empty());
    s.tools[1] = pose(tip, q, 0.0);
    const std::array<std::vector<std::int32_t>, 2> expected{in_line(s.mesh, s.tools[1], wide, 0),
                                                            in_line(s.mesh, s.tools[1], wide, 1)};
    const std::vector<Vec3> x0 = s.mesh.x;
    const std::vector<std::uint8_t> fixed0 = s.mesh.fixed;
    stage.step({1, 0.005, 0.005}, s);
    if (expected[0].empty() && expected[1].empty()) {
      ASSERT_TRUE(s.shared.clips.empty()) << "trial " << trial;
      ASSERT_EQ(clips_dropped(s, 1), 1) << "trial " << trial;
      ASSERT_EQ(s.mesh.fixed, fixed0);
      ++dropped;
      continue;
    }
    ++laid;
    const std::size_t lines = (expected[0].empty() ? 0u : 1u) + (expected[1].empty() ? 0u : 1u);
    ASSERT_EQ(s.shared.clips.size(), lines) << "trial " << trial;
    std::size_t clamped = 0;
    for (const Clip& c : s.shared.clips) {
      ASSERT_EQ(c.kind, Clip::Kind::kStaple);
      ASSERT_EQ(c.tool, 1u);
      const int k = stapler_local(stapler_jaws(s.tools[1], wide), c.hinge_m).y() < 0.0 ? 0 : 1;
      ASSERT_EQ(c.nodes, expected[static_cast<std::size_t>(k)].size()) << "trial " << trial;
      clamped += c.nodes;
    }
    std::size_t newly_fixed = 0;
    for (std::size_t i = 0; i < fixed0.size(); ++i) newly_fixed += s.mesh.fixed[i] != fixed0[i];
    ASSERT_EQ(newly_fixed, clamped);  // nothing else, never a node held already
    for (const auto& line : expected)
      for (std::int32_t k : line) ASSERT_EQ(s.mesh.fixed[static_cast<std::size_t>(k)], 1);
    // Pressed after kStapleSqueezeS: across within the staple height, along and pin unchanged.
    for (int k = 2; k < 2 + static_cast<int>(kStapleSqueezeS / 0.005) + 1; ++k)
      stage.step({static_cast<std::uint64_t>(k), 0.005 * k, 0.005}, s);
    for (const Clip& c : s.shared.clips) {
      const Mat3 rt = c.frame.transpose();
      for (const auto& line : expected)
        for (std::int32_t k : line) {
          const auto uk = static_cast<std::size_t>(k);
          const Vec3 a = rt * (x0[uk] - c.hinge_m), b = rt * (s.mesh.x[uk] - c.hinge_m);
          if (std::abs(a.y()) > kStapleLineHalfWidth + 1e-12) continue;  // the other line's
          ASSERT_LE(std::abs(b.x()), 0.5 * kStapleGap + 1e-12) << "trial " << trial;
          ASSERT_LE(std::abs(b.x()), std::abs(a.x()) + 1e-15);
          ASSERT_NEAR(b.y(), a.y(), 1e-12);
          ASSERT_NEAR(b.z(), a.z(), 1e-12);
        }
    }
  }
  EXPECT_GT(laid, 40);
  EXPECT_GT(dropped, 40);
}

TEST(StapleLines, JawsClosedOnAPlacedClipAreRefusedAndLayNothing) {
  const Scene scene = stapler_scene();
  SimState s;
  s.mesh = test_meshes::kuhn_cube(6, 0.004, 0.0, 1);  // 24 mm cube
  s.tools.resize(2);
  ClipStage stage(scene);
  // A clip across the cube's top at x = 12 mm: the applier points down (-z), opening along y.
  const Eigen::Quaterniond down(Eigen::AngleAxisd(M_PI, Vec3::UnitX()));
  s.tools[0] = pose(Vec3(0.012, 0.012, 0.020), down, 0.6);
  stage.step({0, 0.0, 0.005}, s);
  s.tools[0].jaw_rad = 0.0;
  stage.step({1, 0.005, 0.005}, s);
  ASSERT_EQ(s.shared.clips.size(), 1u);
  // The stapler the same way, its knife 1 mm beside the clip: the clip is in its jaws.
  const Eigen::Quaterniond across =
      down * Eigen::Quaterniond(Eigen::AngleAxisd(0.5 * M_PI, Vec3::UnitZ()));  // pin along +-x
  const auto fire = [&](double x, std::uint64_t step) {
    s.tools[1] = pose(Vec3(x, 0.012, 0.015), across, 0.6);
    stage.step({step, 0.005 * static_cast<double>(step), 0.005}, s);
    s.tools[1].jaw_rad = 0.0;
    stage.step({step + 1, 0.005 * static_cast<double>(step + 1), 0.005}, s);
  };
  const std::vector<std::uint8_t> fixed0 = s.mesh.fixed;
  fire(0.013, 2);
  EXPECT_EQ(stapler_refused(s, 1), 1);
  EXPECT_EQ(clips_dropped(s, 1), 0);
  EXPECT_EQ(s.shared.clips.size(), 1u);
  EXPECT_EQ(s.mesh.fixed, fixed0);
  // Fired 6 mm away from the clip, clear of it: two lines.
  fire(0.018, 4);
  EXPECT_EQ(stapler_refused(s, 1), 1);
  ASSERT_EQ(s.shared.clips.size(), 3u);
  EXPECT_EQ(s.shared.clips[1].kind, Clip::Kind::kStaple);
  EXPECT_EQ(s.shared.clips[2].kind, Clip::Kind::kStaple);
  // Fired across its own first line: refused too.
  fire(0.0185, 6);
  EXPECT_EQ(stapler_refused(s, 1), 2);
  EXPECT_EQ(s.shared.clips.size(), 3u);
}

}  // namespace
}  // namespace serosa::contact
