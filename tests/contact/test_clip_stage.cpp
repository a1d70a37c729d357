// The clips stage's invariants over a thousand random clip appliers closing in, on and beside a
// jittered cube (no FEM: the tissue moves only as the test moves it): a clip clamps exactly the
// free nodes in its jaws' region, presses them to the gap without moving them along or along
// the pin, never takes a node held already, falls away when it closes on nothing, and is carried
// exactly by any rigid motion of the tissue around it.
#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <cmath>
#include <random>

#include "contact/clip_stage.h"
#include "engine/sim_state.h"
#include "engine/tool_geometry.h"
#include "support/test_meshes.h"
#include "support/tool_pose.h"

namespace serosa::contact {
namespace {

Scene applier_scene() {
  Scene scene;
  scene.settings.effects = {Effect::kFem, Effect::kSurface, Effect::kContact, Effect::kClips};
  Tool t;
  t.name = "clipper";
  t.kind = ToolKind::kClipApplier;
  scene.tools.push_back(t);
  return scene;
}

using test_support::pose;

// Nodes in the jaws' region of `ts` opened to `open` rad (the clip's clamp region).
std::vector<std::int32_t> in_jaws(const TetMesh& m, const ToolState& ts, double open) {
  const ToolFrame f = tool_frame(ts);
  std::vector<std::int32_t> out;
  for (std::int32_t n = 0; n < m.num_nodes(); ++n) {
    const Vec3 d = m.x[static_cast<std::size_t>(n)] - f.hinge;
    const Vec3 l(d.dot(f.side), d.dot(f.pin), d.dot(f.forward));
    if (l.z() >= kClipStart && l.z() <= kClipStart + kClipLength &&
        std::abs(l.y()) <= kClipHalfWidth && std::abs(l.x()) <= l.z() * std::tan(0.5 * open) &&
        m.fixed[static_cast<std::size_t>(n)] == 0)
      out.push_back(n);
  }
  return out;
}

TEST(ClipStage, RandomClipsClampExactlyTheirRegionPressItAndRideRigidMotions) {
  const Scene scene = applier_scene();
  std::mt19937 rng(2026);
  std::uniform_real_distribution<double> u(-0.006, 0.026), open(0.35, 1.2);
  std::normal_distribution<double> n(0.0, 1.0);
  int placed = 0, dropped = 0;
  for (int trial = 0; trial < 1000; ++trial) {
    SimState s;
    s.mesh = test_meshes::kuhn_cube(4, 0.005, trial % 3 == 0 ? 0.0 : 0.3, 1 + trial);
    for (std::size_t i = 0; i < s.mesh.fixed.size(); ++i)  // the cube's bottom face held
      s.mesh.fixed[i] = s.mesh.rest[i].z() < 1e-9 ? 1 : 0;
    s.tools.resize(1);
    ClipStage stage(scene);
    Eigen::Quaterniond q(n(rng), n(rng), n(rng), n(rng));
    q.normalize();
    const Vec3 tip(u(rng), u(rng), u(rng));
    const double wide = open(rng);
    s.tools[0] = pose(tip, q, wide);
    stage.step({0, 0.0, 0.005}, s);
    ASSERT_TRUE(s.shared.clips.empty());
    s.tools[0] = pose(tip, q, 0.0);
    const std::vector<std::int32_t> expected = in_jaws(s.mesh, s.tools[0], wide);
    const std::vector<Vec3> x0 = s.mesh.x;
    const std::vector<std::uint8_t> fixed0 = s.mesh.fixed;
    stage.step({1, 0.005, 0.005}, s);
    if (expected.empty()) {
      ASSERT_TRUE(s.shared.clips.empty()) << "trial " << trial;
      ASSERT_EQ(clips_dropped(s, 0), 1) << "trial " << trial;
      ASSERT_EQ(s.mesh.fixed, fixed0);
      ++dropped;
      continue;
    }
    ++placed;
    ASSERT_EQ(s.shared.clips.size(), 1u) << "trial " << trial;
    const Clip clip = s.shared.clips[0];
    ASSERT_EQ(clip.nodes, expected.size()) << "trial " << trial;
    for (std::int32_t k : expected)
      ASSERT_EQ(s.mesh.fixed[static_cast<std::size_t>(k)], 1) << "trial " << trial;
    std::size_t newly_fixed = 0;
    for (std::size_t i = 0; i < fixed0.size(); ++i) newly_fixed += s.mesh.fixed[i] != fixed0[i];
    ASSERT_EQ(newly_fixed, expected.size());  // nothing else, never a node held already
    // Pressed after kClipSqueezeS: across the clip within the gap, along and pin unchanged.
    for (int k = 2; k < 2 + static_cast<int>(kClipSqueezeS / 0.005) + 1; ++k)
      stage.step({static_cast<std::uint64_t>(k), 0.005 * k, 0.005}, s);
    const Mat3 rt = clip.frame.transpose();
    for (std::int32_t k : expected) {
      const auto uk = static_cast<std::size_t>(k);
      const Vec3 a = rt * (x0[uk] - clip.hinge_m), b = rt * (s.mesh.x[uk] - clip.hinge_m);
      ASSERT_LE(std::abs(b.x()), 0.5 * kClipGap + 1e-12) << "trial " << trial;
      ASSERT_LE(std::abs(b.x()), std::abs(a.x()) + 1e-15);  // pressed, never pulled apart
      ASSERT_NEAR(b.y(), a.y(), 1e-12);
      ASSERT_NEAR(b.z(), a.z(), 1e-12);
    }
    // Settled, then every node moved rigidly: the clip and what it clamps go with them.
    const int settle = static_cast<int>(kClipSettleS / 0.005) + 4;
    for (int k = 0; k < settle; ++k)
      stage.step({static_cast<std::uint64_t>(20 + k), 0.1 + 0.005 * k, 0.005}, s);
    const SimState before = s;
    Eigen::Quaterniond r(n(rng), n(rng), n(rng), n(rng));
    r.normalize();
    const Vec3 t(0.01 * n(rng), 0.01 * n(rng), 0.01 * n(rng));
    for (Vec3& x : s.mesh.x) x = r * x + t;
    stage.step({100, 0.5, 0.005}, s);
    const Clip& moved = s.shared.clips[0];
    ASSERT_LT((moved.frame - r.toRotationMatrix() * before.shared.clips[0].frame).norm(), 1e-9)
        << "trial " << trial;
    for (std::int32_t k : expected)
      ASSERT_LT((s.mesh.x[static_cast<std::size_t>(k)] -
                 (r * before.mesh.x[static_cast<std::size_t>(k)] + t))
                    .norm(),
                1e-11)
          << "trial " << trial;
  }
  EXPECT_GT(placed, 250);
  EXPECT_GT(dropped, 250);
}

}  // namespace
}  // namespace serosa::contact
