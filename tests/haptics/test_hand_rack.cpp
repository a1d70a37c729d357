// The handles' instrument rack: carrying a handle's pose from its own trocar to its instrument's
// is exact (the same joints through the other trocar) and the forces come back through it
// unchanged at the joints; exchanges cycle through the instruments waiting; a taken instrument
// enters only once its handle is drawn back to its port.
#include <gtest/gtest.h>

#include <random>

#include "haptics/hand_rack.h"
#include "haptics/random_trocars.h"

namespace serosa::haptics {
namespace {

Vec3 tip(const ToolState& s) { return {s.tip_m[0], s.tip_m[1], s.tip_m[2]}; }
Quat quat(const ToolState& s) {
  return {s.quat_wxyz[0], s.quat_wxyz[1], s.quat_wxyz[2], s.quat_wxyz[3]};
}

TEST(HandRack, CarryingAPoseToAnotherTrocarIsTheSameJointsThroughIt) {
  std::mt19937 rng(7);
  for (int k = 0; k < 2000; ++k) {
    const Trocar a = random_trocar(rng), b = random_trocar(rng);
    const JointState q = random_joints(rng);
    const ToolState carried = trocar_map(a, b).pose(forward(a, q));
    const ToolState direct = forward(b, q);
    EXPECT_LT((tip(carried) - tip(direct)).norm(), 1e-12) << k;
    EXPECT_GT(std::abs(quat(carried).dot(quat(direct))), 1.0 - 1e-12) << k;
    EXPECT_EQ(carried.jaw_rad, direct.jaw_rad);
    // And back again.
    const ToolState back = trocar_map(b, a).pose(carried);
    EXPECT_LT((tip(back) - tip(forward(a, q))).norm(), 1e-12) << k;
  }
}

TEST(HandRack, AForceCarriedBackGivesTheSameJointEfforts) {
  std::mt19937 rng(11);
  std::uniform_real_distribution<double> u(-5.0, 5.0);
  for (int k = 0; k < 2000; ++k) {
    const Trocar handle = random_trocar(rng), instrument = random_trocar(rng);
    const JointState q = random_joints(rng);
    const Vec3 f(u(rng), u(rng), u(rng));
    const JointEffort at_instrument = tip_to_joint(instrument, q, f);
    const JointEffort at_handle =
        tip_to_joint(handle, q, trocar_map(instrument, handle).direction(f));
    EXPECT_NEAR(at_handle.pitch_Nm, at_instrument.pitch_Nm, 1e-12) << k;
    EXPECT_NEAR(at_handle.yaw_Nm, at_instrument.yaw_Nm, 1e-12) << k;
    EXPECT_NEAR(at_handle.insertion_N, at_instrument.insertion_N, 1e-12) << k;
  }
}

HandRack five_instruments() {
  std::mt19937 rng(3);
  std::vector<RackInstrument> items;
  for (std::size_t i = 0; i < 5; ++i) items.push_back({i + 1, random_trocar(rng), {}, 1.0});
  return HandRack(std::move(items), {0, 1});
}

TEST(HandRack, AnExchangeTakesTheNextInstrumentTheOtherHandDoesNotHold) {
  HandRack rack = five_instruments();
  std::vector<std::size_t> right;
  for (int k = 0; k < 5; ++k) right.push_back(*rack.exchange(1));
  EXPECT_EQ(right, (std::vector<std::size_t>{2, 3, 4, 1, 2}));  // never 0: the left hand's
  EXPECT_EQ(rack.held(0), 0u);
  EXPECT_EQ(*rack.exchange(0), 1u);  // the right hand holds 2 now, so 1 is free
}

TEST(HandRack, ATakenInstrumentEntersOnceItsHandleIsDrawnBack) {
  HandRack rack = five_instruments();
  const Trocar& own = rack.handle_trocar(1);
  JointState deep;
  deep.insertion_m = 0.12;
  rack.follow(1, forward(own, deep));
  EXPECT_FALSE(rack.entering(1));
  ASSERT_TRUE(rack.exchange(1));
  EXPECT_TRUE(rack.entering(1));
  rack.follow(1, forward(own, deep));  // still deep in: the new one waits in its port
  EXPECT_TRUE(rack.entering(1));
  JointState back = deep;
  back.insertion_m = 0.5 * kEntryDepthM;
  rack.follow(1, forward(own, back));
  EXPECT_FALSE(rack.entering(1));
  // The instrument's pose is the handle's carried to its own trocar.
  const ToolState at = rack.to_instrument(1, forward(own, back));
  EXPECT_LT((tip(at) - tip(forward(rack.instruments()[2].trocar, back))).norm(), 1e-12);
}

TEST(HandRack, WithOneInstrumentPerHandNothingIsExchanged) {
  std::mt19937 rng(5);
  HandRack rack({{1, random_trocar(rng), {}, 1.0}, {2, random_trocar(rng), {}, 1.0}}, {0, 1});
  EXPECT_FALSE(rack.exchange(0));
  EXPECT_EQ(rack.held(0), 0u);
  EXPECT_FALSE(rack.entering(0));
}

}  // namespace
}  // namespace serosa::haptics
