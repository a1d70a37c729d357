// Script, replay and mouse/keyboard devices, alone and driving the loop.
#include <gtest/gtest.h>

#include <cmath>
#include <stdexcept>

#include "engine/tool_path.h"
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

TEST(MouseKeyboardDevice, MapsCumulativeInputToJoints) {
  MouseMapping map;
  map.rest[0].insertion_m = 0.1;
  MouseKeyboardDevice dev(trocars(), map);
  DeviceSample s;
  ASSERT_TRUE(dev.poll(0.0, s));
  EXPECT_NEAR(s.joints[0].insertion_m, 0.1, 1e-15);
  PointerInput in;
  in.dx_px[0] = 100.0;
  in.dy_px[0] = 1e6;  // far beyond the pitch limit
  in.scroll_steps[0] = -1000.0;
  in.jaw_open[1] = 1;
  in.buttons[1] = 4;
  dev.feed(in);
  ASSERT_TRUE(dev.poll(0.001, s));
  EXPECT_NEAR(s.joints[0].yaw_rad, 0.2, 1e-15);
  EXPECT_NEAR(s.joints[0].pitch_rad, map.max_pitch_rad, 1e-15);
  EXPECT_EQ(s.joints[0].insertion_m, 0.0);
  EXPECT_NEAR(s.joints[1].jaw_rad, map.jaw_open_rad, 1e-15);
  EXPECT_EQ(s.buttons[1], 4u);
  // The pose is the forward kinematics of the joints.
  const ToolState f = forward(trocars()[0], s.joints[0]);
  EXPECT_NEAR(f.tip_m[0], s.pose[0].tip_m[0], 1e-15);
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
  in.scroll_steps[1] = 10.0;  // 5 cm
  dev.feed(in);
  for (int i = 0; i < 5; ++i) loop.tick(1'000'000'000 + i * 1'000'000);
  const ToolState t = loop.tool_state(1).load();
  EXPECT_NEAR(t.tip_m[2], 0.05, 1e-12);
  EXPECT_EQ(t.tick, 5u);
}

}  // namespace
}  // namespace serosa::haptics
