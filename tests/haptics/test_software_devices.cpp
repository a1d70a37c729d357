// Script, replay and mouse/keyboard devices, alone and driving the loop.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <random>
#include <stdexcept>

#include "engine/instrument_hold.h"
#include "engine/scene/tool_path.h"
#include "haptics/haptic_loop.h"
#include "haptics/mouse_device.h"
#include "haptics/replay_device.h"
#include "haptics/script_device.h"
#include "support/test_paths.h"

namespace serosa::haptics {
namespace {

std::array<Trocar, kHandles> trocars() {
  std::array<Trocar, kHandles> t{};
  t[0].pivot_m = Vec3(-0.05, 0.0, 0.0);
  t[1].pivot_m = Vec3(0.05, 0.0, 0.0);
  return t;
}

TEST(ScriptDevice, FollowsThePathInRealTime) {
  // A tool moving straight down the z axis of trocar 0 (consistent with its pivot).
  const ToolPath path = parse_tool_path_text(
      "t,tool,px,py,pz,qw,qx,qy,qz,jaw\n"
      "0.0,grasper,-0.05,0,0.05,1,0,0,0,0.0\n"
      "1.0,grasper,-0.05,0,0.15,1,0,0,0,0.5\n",
      "path.csv");
  ScriptDevice dev(path, {0, std::nullopt}, trocars());
  DeviceSample s;
  ASSERT_TRUE(dev.poll(10.0, s));
  EXPECT_NEAR(s.pose[0].tip_m[2], 0.05, 1e-12);
  ASSERT_TRUE(dev.poll(10.5, s));
  EXPECT_NEAR(s.pose[0].tip_m[2], 0.10, 1e-12);
  EXPECT_NEAR(s.pose[0].jaw_rad, 0.25, 1e-12);
  EXPECT_NEAR(s.joints[0].insertion_m, 0.10, 1e-12);
  EXPECT_NEAR(s.joints[0].pitch_rad, 0.0, 1e-12);
  // The idle handle rests at its pivot.
  EXPECT_NEAR(s.pose[1].tip_m[0], 0.05, 1e-12);
  EXPECT_THROW(ScriptDevice(path, {3, std::nullopt}, trocars()), std::out_of_range);
}

TEST(ScriptDevice, RepositoryPathsLoadAndPlay) {
  const ToolPath path = read_tool_path(std::string(::serosa::test_paths::source_dir()) +
                                       "/config/paths/appendectomy.csv");
  ScriptDevice dev(path, {0, std::nullopt}, trocars());
  DeviceSample s;
  for (double t = 0.0; t < path.end_time_s(); t += 0.25) {
    ASSERT_TRUE(dev.poll(t, s));
    for (double v : s.pose[0].tip_m) ASSERT_TRUE(std::isfinite(v));
    ASSERT_TRUE(std::isfinite(s.joints[0].pitch_rad));
  }
}

TEST(ReplayDevice, PlaysNewestDueSampleAndSkipsMissedOnes) {
  std::vector<DeviceSample> rec(100);
  for (std::size_t i = 0; i < rec.size(); ++i) {
    rec[i].sequence = i + 1;
    rec[i].time_s = 5.0 + 1e-3 * static_cast<double>(i);
    rec[i].joints[0].insertion_m = 1e-3 * static_cast<double>(i);
  }
  ReplayDevice dev(rec);
  DeviceSample s;
  ASSERT_TRUE(dev.poll(100.0, s));
  EXPECT_EQ(s.sequence, 1u);
  EXPECT_EQ(s.time_s, 100.0);        // re-stamped with the loop clock
  EXPECT_FALSE(dev.poll(100.0, s));  // nothing new due
  ASSERT_TRUE(dev.poll(100.001, s));
  EXPECT_EQ(s.sequence, 2u);
  // A 20 ms stall: the newest due sample comes, the 19 in between are skipped.
  ASSERT_TRUE(dev.poll(100.021, s));
  EXPECT_EQ(s.sequence, 22u);
  ASSERT_TRUE(dev.poll(100.5, s));
  EXPECT_EQ(s.sequence, 100u);
  EXPECT_TRUE(dev.finished());
  EXPECT_FALSE(dev.poll(101.0, s));
  std::vector<DeviceSample> bad(2);
  bad[1].time_s = -1.0;
  EXPECT_THROW(ReplayDevice{bad}, std::invalid_argument);
}

Vec3 tip_of(const ToolState& t) { return {t.tip_m[0], t.tip_m[1], t.tip_m[2]}; }

// The tip goes where the drag asks, by exactly the drag, wherever the port allows it: random
// drags of up to 2 cm from random poses, inside the cone and the insertion range.
TEST(MouseKeyboardDevice, TheTipFollowsTheDragWhereThePortAllows) {
  MouseMapping map;
  map.ease_s = 0.0;
  map.rest[0].insertion_m = 0.1;
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> u(-0.02, 0.02);
  MouseKeyboardDevice dev(trocars(), map);
  PointerInput in;
  DeviceSample s;
  ASSERT_TRUE(dev.poll(0.0, s));
  int reachable = 0;
  for (int i = 0; i < 2000; ++i) {
    const Vec3 before = tip_of(s.pose[0]);
    const Vec3 move(u(rng), u(rng), u(rng));
    for (int k = 0; k < 3; ++k) in.move_m[0][static_cast<std::size_t>(k)] += move[k];
    dev.feed(in);
    ASSERT_TRUE(dev.poll(0.001 * (i + 1), s));
    const Vec3 goal = before + move;
    const Vec3 local = goal - trocars()[0].pivot_m;
    const double cone = std::acos(std::clamp(local.normalized().z(), -1.0, 1.0));
    const Vec3 after = tip_of(s.pose[0]);
    // Never outside what the port allows.
    const Vec3 now = after - trocars()[0].pivot_m;
    ASSERT_LE(std::acos(std::clamp(now.normalized().z(), -1.0, 1.0)), map.max_cone_rad + 1e-9);
    ASSERT_GE(now.norm(), map.min_insertion_m - 1e-12);
    ASSERT_LE(now.norm(), map.max_insertion_m + 1e-12);
    if (cone < map.max_cone_rad && local.norm() > map.min_insertion_m &&
        local.norm() < map.max_insertion_m) {
      ++reachable;
      ASSERT_LT((after - goal).norm(), 1e-12) << i;
    } else {
      ASSERT_LE((after - goal).norm(), (before - goal).norm() + 1e-12) << i;  // as near as it can
    }
  }
  EXPECT_GT(reachable, 1000);
}

// Depth steps insert along the shaft, roll steps roll, Home brings the handle back to rest, the
// jaws open to the share of the instrument's range asked for, and the buttons pass through.
TEST(MouseKeyboardDevice, DepthRollHomeJawsAndButtons) {
  MouseMapping map;
  map.ease_s = 0.0;
  map.rest[0].insertion_m = 0.1;
  map.jaw_max_rad = {1.2, 0.7};
  MouseKeyboardDevice dev(trocars(), map);
  DeviceSample s;
  ASSERT_TRUE(dev.poll(0.0, s));
  EXPECT_NEAR(s.joints[0].insertion_m, 0.1, 1e-15);
  PointerInput in;
  in.depth_steps[0] = 5.0;
  in.roll_steps[0] = -2.0;
  in.jaw_fraction = {1.0, 0.5};
  in.buttons[1] = 4;
  dev.feed(in);
  ASSERT_TRUE(dev.poll(10.0, s));  // long enough for the jaws' speed
  EXPECT_NEAR(s.joints[0].insertion_m, 0.1 + 5.0 * map.m_per_step, 1e-12);
  EXPECT_NEAR(s.joints[0].roll_rad, -0.2, 1e-12);
  EXPECT_NEAR(s.joints[0].jaw_rad, 1.2, 1e-12);
  EXPECT_NEAR(s.joints[1].jaw_rad, 0.35, 1e-12);
  EXPECT_EQ(s.buttons[1], 4u);
  in.depth_steps[0] = -1e4;  // far beyond the shortest insertion
  dev.feed(in);
  ASSERT_TRUE(dev.poll(10.001, s));
  EXPECT_NEAR(s.joints[0].insertion_m, map.min_insertion_m, 1e-15);
  in.move_m[0] = {0.03, 0.0, 0.0};
  dev.feed(in);
  ASSERT_TRUE(dev.poll(10.002, s));
  in.homes[0] = 1;
  dev.feed(in);
  ASSERT_TRUE(dev.poll(10.003, s));
  EXPECT_NEAR(s.joints[0].insertion_m, 0.1, 1e-15);
  EXPECT_NEAR(s.joints[0].roll_rad, 0.0, 1e-15);
  EXPECT_NEAR(s.joints[0].jaw_rad, 1.2, 1e-12);  // Home leaves the jaws as they are
  // The pose is the forward kinematics of the joints.
  const ToolState f = forward(trocars()[0], s.joints[0]);
  EXPECT_NEAR(f.tip_m[0], s.pose[0].tip_m[0], 1e-15);
}

// A frame's worth of input arriving at once is spread over the ticks that follow: no tick moves
// the tip by more than a share of it, and none of it is lost. The jaws move at their speed.
TEST(MouseKeyboardDevice, EasesAFramesInputOverTheTicks) {
  MouseMapping map;
  map.rest[0].insertion_m = 0.1;
  MouseKeyboardDevice dev(trocars(), map);
  DeviceSample s;
  ASSERT_TRUE(dev.poll(0.0, s));
  const Vec3 start = tip_of(s.pose[0]);
  PointerInput in;
  in.move_m[0] = {0.01, 0.0, 0.0};
  in.jaw_fraction[0] = 1.0;
  dev.feed(in);
  double largest = 0.0;
  Vec3 last = start;
  for (int i = 1; i <= 500; ++i) {
    ASSERT_TRUE(dev.poll(0.001 * i, s));
    largest = std::max(largest, (tip_of(s.pose[0]) - last).norm());
    last = tip_of(s.pose[0]);
    if (i == 100) {
      EXPECT_NEAR(s.joints[0].jaw_rad, 0.4, 1e-9);  // 4 rad/s for 0.1 s
    }
  }
  EXPECT_LT(largest, 0.1 * 0.01);  // the 1 cm frame came in more than ten ticks
  EXPECT_LT((last - (start + Vec3(0.01, 0.0, 0.0))).norm(), 1e-6);
  EXPECT_NEAR(s.joints[0].jaw_rad, map.jaw_max_rad[0], 1e-12);
}

// After an exchange the handle is drawn back to its port and waits there, jaws closed, for as
// long as the stage has not seen it so (a slow solver step must not miss it); once admitted it
// inserts the new instrument at the entry speed to its rest, and X presses the button until the
// reseat (at most kPressS).
TEST(MouseKeyboardDevice, AReseatedHandleWaitsDrawnBackUntilAdmittedThenEnters) {
  MouseMapping map;
  map.rest[0].insertion_m = 0.1;
  map.rest[1].insertion_m = 0.1;
  MouseKeyboardDevice dev(trocars(), map);
  DeviceSample s;
  ASSERT_TRUE(dev.poll(0.0, s));
  PointerInput in;
  in.exchanges[1] = 1;
  dev.feed(in);
  ASSERT_TRUE(dev.poll(0.001, s));
  EXPECT_EQ(s.buttons[1] & serosa::kExchangeButton, serosa::kExchangeButton);
  ASSERT_TRUE(dev.poll(0.001 + 0.5 * kPressS, s));
  EXPECT_EQ(s.buttons[1] & serosa::kExchangeButton,
            serosa::kExchangeButton);  // no reseat yet: still pressed
  JointState rest;
  rest.insertion_m = 0.08;
  rest.jaw_rad = 0.5;
  dev.reseat(1, rest, 0.7, Quat::Identity());
  double t = 0.001 + 0.5 * kPressS;
  for (int i = 0; i < 10'000; ++i) {  // 10 s unadmitted: it stays drawn back
    t += 0.001;
    ASSERT_TRUE(dev.poll(t, s));
    ASSERT_EQ(s.joints[1].insertion_m, map.min_insertion_m) << i;
    ASSERT_EQ(s.buttons[1] & serosa::kExchangeButton, 0u) << i;  // the reseat released the button
  }
  EXPECT_EQ(s.joints[1].jaw_rad, 0.0);
  dev.admit(1);
  const double entry_s = (0.08 - map.min_insertion_m) / map.entry_speed_m_s;
  double reached = -1.0, last = s.joints[1].insertion_m;
  for (int i = 1; i <= 2000 && reached < 0.0; ++i) {
    ASSERT_TRUE(dev.poll(t + 0.001 * i, s));
    EXPECT_LE(s.joints[1].insertion_m - last, map.entry_speed_m_s * 0.001 + 1e-12);
    last = s.joints[1].insertion_m;
    if (s.joints[1].insertion_m == 0.08) reached = 0.001 * i;
  }
  EXPECT_NEAR(reached, entry_s, 0.002);
  EXPECT_EQ(s.joints[0].insertion_m, map.rest[0].insertion_m);  // the other hand stays put
}

TEST(SoftwareDevices, DriveTheLoop) {
  ContactModelChannel ch;
  HapticLoopConfig c;
  c.realtime = false;
  c.gap_monitor = false;
  c.trocars = trocars();
  MouseKeyboardDevice dev(trocars());
  HapticLoop loop(dev, ch, c);
  PointerInput in;
  in.depth_steps[1] = 10.0;  // 3 cm in from the port
  dev.feed(in);
  for (int i = 0; i < 500; ++i) loop.tick(1'000'000'000 + i * 1'000'000);
  const ToolState t = loop.tool_state(1).load();
  EXPECT_NEAR(t.tip_m[2], 0.03, 1e-6);
  EXPECT_EQ(t.tick, 500u);
}

}  // namespace
}  // namespace serosa::haptics
