// The smoke stage (cutting/smoke_stage.h): nodes a hook coagulates raise puffs there (a few a
// step), which rise against gravity, swell, thin out and clear; never more than the ring holds,
// in storage that a step does not reallocate; a restored stage continues bit for bit.
#include <gtest/gtest.h>

#include <vector>

#include "cutting/smoke_stage.h"
#include "engine/input_error.h"
#include "engine/kuhn_grid.h"
#include "engine/scene/scene.h"
#include "engine/sim_state.h"
#include "support/block_copy.h"

namespace serosa::cutting {
namespace {

constexpr double kDt = 0.005;

Scene scene() {
  Scene s;
  s.settings.dt_s = kDt;
  s.settings.gravity_mps2 = Vec3(0.0, 0.0, -9.81);
  return s;
}

SimState slab() {
  SimState s;
  s.mesh = kuhn_grid(6, 0.005);
  s.blocks.cutting.coagulated.assign(s.mesh.x.size(), 0);
  return s;
}

void run(SmokeStage& stage, SimState& s, int steps) {
  for (int k = 0; k < steps; ++k) {
    stage.step(StepContext{s.step, s.time_s, kDt}, s);
    s.time_s += kDt;
    ++s.step;
  }
}

TEST(SmokeStage, CoagulationRaisesPuffsThatRiseSwellThinAndClear) {
  SmokeStage stage(scene());
  SimState s = slab();
  run(stage, s, 5);
  EXPECT_TRUE(s.shared.smoke.empty());
  for (std::size_t i = 0; i < 10; ++i) s.blocks.cutting.coagulated[i] = 1;  // ten nodes at once
  run(stage, s, 1);
  ASSERT_EQ(s.shared.smoke.size(), static_cast<std::size_t>(SmokeStage::kPuffsPerStep));
  const SmokePuff first = s.shared.smoke[0];
  EXPECT_NEAR((first.at_m - s.mesh.x[0]).norm(), 0.0, 0.001);
  run(stage, s, 1);  // the same marks raise no more puffs
  ASSERT_EQ(s.shared.smoke.size(), static_cast<std::size_t>(SmokeStage::kPuffsPerStep));
  run(stage, s, 100);
  const SmokePuff later = s.shared.smoke[0];
  EXPECT_NEAR(later.at_m.z() - first.at_m.z(), SmokeStage::kRiseMps * 101 * kDt, 1e-9);
  EXPECT_GT(later.radius_m, first.radius_m);
  EXPECT_LT(later.density, first.density);
  run(stage, s, static_cast<int>(SmokeStage::kLifeS / kDt));
  EXPECT_TRUE(s.shared.smoke.empty());
}

TEST(SmokeStage, TheRingHoldsAtMostItsPuffsAndAStepDoesNotReallocate) {
  SmokeStage stage(scene());
  SimState s = slab();
  run(stage, s, 1);
  const SmokePuff* storage = s.shared.smoke.data();
  for (std::size_t i = 0; i < s.mesh.x.size(); ++i) {
    s.blocks.cutting.coagulated[i] = 1;
    run(stage, s, 1);
    ASSERT_LE(s.shared.smoke.size(), SmokeStage::kMaxPuffs);
    ASSERT_EQ(s.shared.smoke.data(), storage) << "step " << i;
  }
  EXPECT_EQ(s.shared.smoke.size(), SmokeStage::kMaxPuffs);
}

TEST(SmokeStage, ARestoredStageContinuesBitForBit) {
  SmokeStage a(scene());
  SimState s = slab();
  for (std::size_t i = 0; i < 40; i += 3) {
    s.blocks.cutting.coagulated[i] = 1;
    run(a, s, 7);
  }
  SimState r = s;
  r.shared.smoke.clear();
  r.blocks.smoke = {};
  r.blocks.smoke = test_blocks::copy(s.blocks.smoke);
  SmokeStage b(scene());
  b.adopt(r);
  for (std::size_t i = 40; i < 80; i += 2) {
    s.blocks.cutting.coagulated[i] = r.blocks.cutting.coagulated[i] = 1;
    run(a, s, 3);
    run(b, r, 3);
  }
  ASSERT_EQ(r.shared.smoke.size(), s.shared.smoke.size());
  for (std::size_t k = 0; k < s.shared.smoke.size(); ++k) {
    EXPECT_EQ(r.shared.smoke[k].at_m, s.shared.smoke[k].at_m);
    EXPECT_EQ(r.shared.smoke[k].density, s.shared.smoke[k].density);
  }
  SimState small = slab();
  small.mesh.x.resize(4);
  small.blocks.smoke = test_blocks::copy(s.blocks.smoke);
  SmokeStage c(scene());
  EXPECT_THROW(c.adopt(small), BlockMismatch);
}

}  // namespace
}  // namespace serosa::cutting
