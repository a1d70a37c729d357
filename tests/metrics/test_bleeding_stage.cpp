// The bleeding stage (metrics/bleeding_stage.h) on a slab lying on its support: the cut end bleeds
// the mean arterial flow over whole heartbeats, the pool grows with what was shed and stains only
// what it reaches (for good); a ligature placed over the end or coagulation after the cutting
// stroke closes it, the stroke's own coagulation does not; a restored stage continues bit for
// bit, and a snapshot that does not fit the mesh is an error.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <vector>

#include "engine/input_error.h"
#include "engine/kuhn_grid.h"
#include "engine/scene/scene.h"
#include "engine/sim_state.h"
#include "metrics/bleeding_stage.h"
#include "support/block_copy.h"

namespace serosa::metrics {
namespace {

constexpr double kDt = 0.005;

Scene floor_scene() {
  Scene s;
  s.settings.dt_s = kDt;
  s.settings.gravity_mps2 = Vec3(0.0, 0.0, -9.81);
  s.supports.push_back({"wall", Vec3(0.0, 0.0, -0.002), Vec3::UnitZ()});
  return s;
}

// A 4 x 4 x 1 cm slab of 1 cm tets (z from 0 to 1 cm), bleeding from its top corner.
SimState slab() {
  SimState s;
  s.mesh = kuhn_grid(4, 0.01);
  for (Vec3& x : s.mesh.x) x.z() *= 0.25;
  s.blocks.cutting.coagulated.assign(s.mesh.x.size(), 0);
  return s;
}

void run(BleedingStage& stage, SimState& s, int steps) {
  for (int k = 0; k < steps; ++k) {
    StepContext ctx{s.step, s.time_s, kDt};
    stage.step(ctx, s);
    s.time_s += kDt;
    ++s.step;
  }
}

TEST(BleedingStage, ShedsTheMeanFlowAndThePoolStainsOnlyWhatItReaches) {
  BleedingStage stage(floor_scene());
  SimState s = slab();
  run(stage, s, 10);  // nothing bleeds: nothing published
  EXPECT_TRUE(s.shared.blood.empty());
  EXPECT_TRUE(s.blocks.bleeding.stain.empty());
  const Vec3 cut(0.0, 0.0, 0.01);
  s.shared.bleeds.emplace_back(cut, s.time_s);
  const double since = s.time_s;
  run(stage, s, static_cast<int>(std::lround(4.0 / BleedingStage::kHeartRateHz / kDt)));
  ASSERT_EQ(s.shared.blood.size(), 1u);
  const Blood& b = s.shared.blood[0];
  const double elapsed = s.time_s - since;
  EXPECT_NEAR(b.shed_m3, BleedingStage::kFlowM3PerS * elapsed, 0.02 * b.shed_m3);
  EXPECT_NEAR(b.pool_radius_m,
              std::sqrt(b.shed_m3 / (std::numbers::pi * BleedingStage::kPoolDepthM)), 1e-12);
  EXPECT_GT(b.pulse, 0.0);
  // The pool lies on the support, straight below the cut.
  EXPECT_NEAR(b.pool_m.z(), -0.002, 1e-12);
  EXPECT_NEAR((b.pool_m - cut).head<2>().norm(), 0.0, 1e-12);
  ASSERT_EQ(s.blocks.bleeding.stain.size(), s.mesh.x.size());
  for (std::size_t i = 0; i < s.mesh.x.size(); ++i) {
    const double d = (s.mesh.x[i] - b.pool_m).norm();
    if (d >= b.pool_radius_m) {
      EXPECT_EQ(s.blocks.bleeding.stain[i], 0.0f) << i;
    } else if (d < 0.5 * b.pool_radius_m) {
      EXPECT_GT(s.blocks.bleeding.stain[i], 0.9f) << i;
    }
  }
  // Stains stay where the tissue moves away.
  const std::vector<float> before = s.blocks.bleeding.stain;
  for (Vec3& x : s.mesh.x) x.x() += 0.2;
  run(stage, s, 1);
  for (std::size_t i = 0; i < before.size(); ++i) EXPECT_GE(s.blocks.bleeding.stain[i], before[i]);
}

TEST(BleedingStage, ALigatureOverTheEndOrLaterCoagulationClosesItTheStrokesOwnDoesNot) {
  for (const bool by_clip : {true, false}) {
    BleedingStage stage(floor_scene());
    SimState s = slab();
    const Vec3 cut(0.0, 0.0, 0.01);
    s.shared.bleeds.emplace_back(cut, s.time_s);
    const double since = s.time_s;
    // The cutting stroke coagulates the cut end's node as it divides.
    s.blocks.cutting.coagulated[0] = 1;
    for (std::size_t i = 0; i < s.mesh.x.size(); ++i)
      if ((s.mesh.x[i] - cut).norm() < 1e-9) s.blocks.cutting.coagulated[i] = 1;
    run(stage, s, static_cast<int>(std::lround(1.2 * BleedingStage::kOwnStrokeS / kDt)));
    ASSERT_EQ(s.shared.blood.size(), 1u);
    EXPECT_GT(s.shared.blood[0].pulse, 0.0) << "the stroke's own coagulation closed it";
    if (by_clip) {
      Clip c;
      c.hinge_m = cut - Vec3(0.0, 0.0, 0.003);
      c.placed_s = s.time_s;
      s.shared.clips.push_back(c);
    } else {
      // A node near the end, coagulated after the stroke.
      std::size_t near = 0;
      double best = 1e9;
      for (std::size_t i = 0; i < s.mesh.x.size(); ++i) {
        const double d = (s.mesh.x[i] - cut).norm();
        if (d > 1e-9 && d < best && s.blocks.cutting.coagulated[i] == 0) {
          best = d;
          near = i;
        }
      }
      s.mesh.x[near] = cut + Vec3(0.002, 0.0, 0.0);
      s.blocks.cutting.coagulated[near] = 1;
    }
    run(stage, s, 1);
    const double shed = s.shared.blood[0].shed_m3;
    EXPECT_EQ(s.shared.blood[0].pulse, 0.0) << (by_clip ? "clip" : "coagulation");
    run(stage, s, 100);
    EXPECT_EQ(s.shared.blood[0].shed_m3, shed);  // nothing more is shed
    EXPECT_GT(shed, 0.0);
    EXPECT_LT(shed, BleedingStage::kFlowM3PerS * (s.time_s - since));
  }
}

TEST(BleedingStage, ARestoredStageContinuesBitForBitAndABadSnapshotIsAnError) {
  BleedingStage a(floor_scene());
  SimState s = slab();
  s.shared.bleeds.emplace_back(Vec3(0.01, 0.01, 0.01), 0.0);
  run(a, s, 137);
  SimState r = s;
  r.shared.blood.clear();
  r.blocks.bleeding = {};
  r.blocks.bleeding = test_blocks::copy(s.blocks.bleeding);
  BleedingStage b(floor_scene());
  b.adopt(r);
  ASSERT_EQ(r.shared.blood.size(), s.shared.blood.size());
  EXPECT_EQ(r.blocks.bleeding.stain, s.blocks.bleeding.stain);
  run(a, s, 200);
  run(b, r, 200);
  EXPECT_EQ(r.shared.blood[0].shed_m3, s.shared.blood[0].shed_m3);
  EXPECT_EQ(r.shared.blood[0].pool_radius_m, s.shared.blood[0].pool_radius_m);
  EXPECT_EQ(r.blocks.bleeding.stain, s.blocks.bleeding.stain);

  SimState small = slab();
  small.mesh.x.resize(3);
  small.blocks.bleeding = test_blocks::copy(s.blocks.bleeding);
  BleedingStage c(floor_scene());
  EXPECT_THROW(c.adopt(small), BlockMismatch);
}

}  // namespace
}  // namespace serosa::metrics
