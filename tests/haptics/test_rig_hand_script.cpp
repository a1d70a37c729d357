// A scripted hand on a rig handle: it follows the instrument its hand holds, carried to the
// handle's trocar; at each exchange it presses the handle button, draws the handle back to its
// port long enough for the stage to see it, and pushes the new instrument in, never jumping; a
// path whose hands take the instruments out of the scene's order, or take one the rig does not
// have, is a clear error naming the hand, the time and the instrument.
#include <gtest/gtest.h>

#include <cstdio>
#include <random>
#include <string>

#include "engine/input_error.h"
#include "haptics/emulated_hands.h"
#include "haptics/random_trocars.h"
#include "haptics/rig_hand_script.h"

namespace serosa::haptics {
namespace {

Vec3 tip(const ToolState& s) { return {s.tip_m[0], s.tip_m[1], s.tip_m[2]}; }

// One row of `tool` at time t with joints q through trocar `tr`, held by `hand`.
std::string row(double t, const std::string& tool, const Trocar& tr, const JointState& q,
                const char* hand) {
  const ToolState s = forward(tr, q);
  char buf[320];
  std::snprintf(buf, sizeof buf, "%.4f,%s,%.12f,%.12f,%.12f,%.12f,%.12f,%.12f,%.12f,%.6f,0,%s\n", t,
                tool.c_str(), s.tip_m[0], s.tip_m[1], s.tip_m[2], s.quat_wxyz[0], s.quat_wxyz[1],
                s.quat_wxyz[2], s.quat_wxyz[3], q.jaw_rad, hand);
  return buf;
}

JointState slow_joints(std::mt19937& rng) {
  JointState q = random_joints(rng);
  q.pitch_rad *= 0.5;
  q.insertion_m = 0.04 + 0.5 * q.insertion_m;  // 4-19 cm in
  return q;
}

// Three instruments for the right hand in turn (a from 0 s, b from 1 s, c from 2 s), each moving
// slowly through its own trocar; the left holds d throughout.
struct Case {
  std::array<Trocar, 4> trocar;
  ToolPath path;
};

Case random_case(std::mt19937& rng) {
  Case c;
  for (Trocar& t : c.trocar) t = random_trocar(rng);
  const char* names[] = {"a", "b", "c", "d"};
  std::string text = "t,tool,px,py,pz,qw,qx,qy,qz,jaw,buttons,hand\n";
  for (int k = 0; k < 4; ++k) {
    for (int i = 0; i <= 3; ++i) {
      const double t = i;
      const char* hand =
          k == 3                                                                           ? "left"
          : (k == 0 && t < 1.0) || (k == 1 && t >= 1.0 && t < 2.0) || (k == 2 && t >= 2.0) ? "right"
                                                                                           : "port";
      text += row(t, names[k], c.trocar[static_cast<std::size_t>(k)], slow_joints(rng), hand);
    }
  }
  c.path = parse_tool_path_text(text, "hands.csv");
  return c;
}

RigHand right_hand(const Case& c, const Trocar& handle) {
  std::vector<TrocarMap> maps;
  for (std::size_t k = 0; k < 4; ++k) maps.push_back(trocar_map(c.trocar[k], handle));
  return plan_rig_hand(c.path, Hand::kRight, 0, handle, maps);
}

TEST(RigHandScript, TheHandColumnGivesEachHandItsInstrumentsInTurn) {
  std::mt19937 rng(5);
  const Case c = random_case(rng);
  const std::vector<HandChange> right = hand_changes(c.path, Hand::kRight);
  ASSERT_EQ(right.size(), 3u);
  EXPECT_EQ(c.path.tools[right[0].tool], "a");
  EXPECT_EQ(c.path.tools[right[1].tool], "b");
  EXPECT_EQ(right[1].t_s, 1.0);
  EXPECT_EQ(c.path.tools[right[2].tool], "c");
  EXPECT_EQ(right[2].t_s, 2.0);
  const RigHand plan = right_hand(c, c.trocar[0]);
  ASSERT_EQ(plan.exchanges.size(), 2u);  // it holds a first: no exchange for it
  EXPECT_EQ(held_tool(plan, 0.5), 0u);
  EXPECT_EQ(held_tool(plan, 1.5), 1u);
  EXPECT_EQ(held_tool(plan, 2.5), 2u);
  ASSERT_EQ(hand_changes(c.path, Hand::kLeft).size(), 1u);
}

// Over many random trocars and paths, sampled every 0.1 ms: the handle never jumps; the button
// is down exactly while an exchange asks for it; the handle stays within kEntryDepthM of its
// port at least kDrawnBackHoldS after each; outside the exchanges it is exactly the held
// instrument's joints; and it has met the new instrument's path once it could have.
TEST(RigHandScript, AnExchangeDrawsTheHandleBackAndPushesTheNextInWithoutAJump) {
  std::mt19937 rng(17);
  for (int trial = 0; trial < 40; ++trial) {
    const Case c = random_case(rng);
    const Trocar handle = random_trocar(rng);
    const RigHand plan = right_hand(c, handle);
    Vec3 last = tip(forward(handle, hand_joints(c.path, plan, 0.0)));
    std::array<double, 2> back_s{};
    double largest = 0.0;
    for (int i = 1; i <= 30'000; ++i) {
      const double t = 1e-4 * i;
      const JointState q = hand_joints(c.path, plan, t);
      const Vec3 now = tip(forward(handle, q));
      largest = std::max(largest, (now - last).norm());
      last = now;
      const std::size_t e = t >= 2.0 ? 1 : t >= 1.0 ? 0 : 2;
      const double since = e < 2 ? t - plan.exchanges[e].t_s : 1.0;
      const bool pressed = (hand_buttons(c.path, plan, t) & kExchangeButton) != 0;
      ASSERT_EQ(pressed, since < kPressHoldS) << trial << " t " << t;
      if (e < 2 && q.insertion_m <= kEntryDepthM) back_s[e] += 1e-4;
      if (since >= 0.8) {  // long after the exchange: the instrument's own joints, carried
        const std::size_t k = *held_tool(plan, t);
        const JointState own = inverse(c.trocar[k], sample(c.path, k, t));
        ASSERT_NEAR(q.insertion_m, own.insertion_m, 1e-9) << trial << " t " << t;
        ASSERT_NEAR(q.jaw_rad, own.jaw_rad, 1e-9) << trial << " t " << t;
      }
    }
    // 0.1 ms at the fastest the hand moves (the shaft turning at the port while drawn back)
    EXPECT_LT(largest, 2e-3) << trial;
    for (double s : back_s) EXPECT_GE(s, kDrawnBackHoldS - 2e-4) << trial;
  }
}

// The rack's scene: four instruments, the handles holding the first two.
struct RackScene {
  Scene scene;
  std::unique_ptr<HandRack> rack;
};

RackScene rack_scene(const std::vector<std::string>& names) {
  RackScene r;
  std::mt19937 rng(9);
  std::vector<RackInstrument> items;
  for (std::size_t i = 0; i < names.size(); ++i) {
    Tool t;
    t.name = names[i];
    r.scene.tools.push_back(t);
    items.push_back({i, random_trocar(rng), {}, 1.0});
  }
  r.rack = std::make_unique<HandRack>(std::move(items),
                                      std::array<std::optional<std::size_t>, kHandles>{0, 1});
  return r;
}

// The right hand holds s first, then takes `order` in turn, one a second.
ToolPath right_takes(const std::vector<std::string>& order) {
  std::string text = "t,tool,px,py,pz,qw,qx,qy,qz,jaw,buttons,hand\n";
  text += "0,g,0,0,0.1,1,0,0,0,0,0,left\n0,s,0,0,0.1,1,0,0,0,0,0,right\n";
  text += "1,s,0,0,0.1,1,0,0,0,0,0,port\n";
  for (std::size_t i = 0; i < order.size(); ++i) {
    const std::string t = std::to_string(i + 1);
    text += t + "," + order[i] + ",0,0,0.1,1,0,0,0,0,0,right\n";
    text += std::to_string(i + 2) + "," + order[i] + ",0,0,0.1,1,0,0,0,0,0,port\n";
  }
  return parse_tool_path_text(text, "order.csv");
}

TEST(EmulatedHands, PlansTheExchangesTheRackWillMake) {
  const RackScene r = rack_scene({"g", "s", "c", "h"});
  const auto hands = emulated_hands(r.scene, *r.rack, right_takes({"c", "h"}));
  ASSERT_TRUE(hands[0] && hands[1]);
  EXPECT_TRUE(hands[0]->exchanges.empty());
  ASSERT_EQ(hands[1]->exchanges.size(), 2u);
}

TEST(EmulatedHands, AnotherOrderThanTheScenesIsAClearError) {
  const RackScene r = rack_scene({"g", "s", "c", "h"});
  try {
    (void)emulated_hands(r.scene, *r.rack, right_takes({"h", "c"}));
    FAIL() << "no error";
  } catch (const InputError& e) {
    const std::string what = e.what();
    EXPECT_NE(what.find("order.csv"), std::string::npos) << what;
    EXPECT_NE(what.find("right hand takes 'h' at 1.000 s"), std::string::npos) << what;
    EXPECT_NE(what.find("brings in 'c'"), std::string::npos) << what;
  }
}

TEST(EmulatedHands, AnInstrumentTheRigDoesNotHaveIsAClearError) {
  const RackScene r = rack_scene({"g", "s", "c", "h"});
  try {
    (void)emulated_hands(r.scene, *r.rack, right_takes({"c", "stapler"}));
    FAIL() << "no error";
  } catch (const InputError& e) {
    const std::string what = e.what();
    EXPECT_NE(what.find("right hand takes 'stapler' at 2.000 s, which is not one of the rig's"),
              std::string::npos)
        << what;
    EXPECT_NE(what.find("g, s, c, h"), std::string::npos) << what;
  }
}

}  // namespace
}  // namespace serosa::haptics
