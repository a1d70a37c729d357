// The unmodified libusb rig driver (UsbRig) against the umockdev-emulated rig (EmulatedRig):
// normal transfers, short packet, bad checksum, bad version, endpoint stall, unplug and replug,
// the firmware watchdog, and the whole HapticLoop over USB. Each test re-runs itself under
// umockdev-wrapper (the preload library must be in the process from its start).
#include <gtest/gtest.h>
#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <cmath>
#include <cstdlib>
#include <functional>
#include <sstream>
#include <string>
#include <thread>
#include <vector>

#include "engine/scene/tool_path.h"
#include "haptics/emulated_rig.h"
#include "haptics/haptic_loop.h"
#include "haptics/usb_rig.h"
#include "umockdev_rerun.h"

namespace serosa::haptics {
namespace {

using test_support::rerun_under_umockdev;

#define SEROSA_UNDER_UMOCKDEV()                                                     \
  if (!umockdev_preload_active()) {                                                 \
    const int rc = rerun_under_umockdev();                                          \
    ASSERT_EQ(rc, 0) << "the test failed under umockdev-wrapper (see its output); " \
                        "-2 means umockdev-wrapper was not found";                  \
    return;                                                                         \
  }

bool wait_for(const std::function<bool()>& pred, double seconds) {
  const auto end = std::chrono::steady_clock::now() + std::chrono::duration<double>(seconds);
  while (std::chrono::steady_clock::now() < end) {
    if (pred()) return true;
    std::this_thread::sleep_for(std::chrono::milliseconds(2));
  }
  return pred();
}

// A tool path holding handle 0 still at joints q (consistent with the default trocar).
ToolPath still_path(const JointState& q) {
  const ToolState s = forward(Trocar{}, q);
  std::ostringstream os;
  os.precision(17);
  os << "t,tool,px,py,pz,qw,qx,qy,qz,jaw\n";
  for (double t : {0.0, 100.0}) {
    os << t << ",grasper," << s.tip_m[0] << ',' << s.tip_m[1] << ',' << s.tip_m[2] << ','
       << s.quat_wxyz[0] << ',' << s.quat_wxyz[1] << ',' << s.quat_wxyz[2] << ',' << s.quat_wxyz[3]
       << ',' << s.jaw_rad << '\n';
  }
  return parse_tool_path_text(os.str(), "still.csv");
}

JointState test_joints() {
  JointState q;
  q.pitch_rad = 0.3;
  q.yaw_rad = -0.2;
  q.roll_rad = 0.5;
  q.insertion_m = 0.12;
  q.jaw_rad = 0.4;
  return q;
}

EmulatedRigConfig rig_config() {
  EmulatedRigConfig c;
  c.path = still_path(test_joints());
  c.tool_of_handle = {0, std::nullopt};
  return c;
}

TEST(UsbRigEmulated, NormalTransfersAndForceCommands) {
  SEROSA_UNDER_UMOCKDEV();
  EmulatedRig rig(rig_config());
  UsbRig usb;
  ASSERT_TRUE(wait_for([&] { return usb.connected(); }, 5.0));
  ASSERT_TRUE(wait_for([&] { return usb.counters().packets >= 100; }, 10.0));
  DeviceSample s;
  ASSERT_TRUE(usb.poll(0.0, s));
  const JointState q = test_joints();
  const double count_rad = 2.0 * 3.14159265358979 / 4096.0;
  EXPECT_NEAR(s.joints[0].pitch_rad, q.pitch_rad, count_rad);
  EXPECT_NEAR(s.joints[0].yaw_rad, q.yaw_rad, count_rad);
  EXPECT_NEAR(s.joints[0].roll_rad, q.roll_rad, count_rad);
  EXPECT_NEAR(s.joints[0].jaw_rad, q.jaw_rad, count_rad);
  EXPECT_NEAR(s.joints[0].insertion_m, q.insertion_m, 1e-4);
  EXPECT_EQ(s.joints[1].insertion_m, 0.0);
  const UsbRigCounters n = usb.counters();
  EXPECT_EQ(n.too_short + n.bad_checksum + n.bad_type_version, 0u);
  // Force commands travel to the firmware and are decoded there.
  DeviceCommand cmd;
  cmd.enable = true;
  cmd.effort[0].pitch_Nm = 0.25;
  cmd.effort[1].insertion_N = -1.5;
  // A command is dropped while the previous OUT transfer is in flight (docs/rig-protocol.md), so
  // keep commanding, as the 1 kHz loop does, until the firmware has decoded a few.
  cmd.state_sequence = s.sequence;
  ASSERT_TRUE(wait_for(
      [&] {
        usb.command(cmd);
        std::this_thread::sleep_for(std::chrono::microseconds(500));
        return rig.stats().forces_ok >= 5;
      },
      10.0));
  const EmulatedRigStats st = rig.stats();
  EXPECT_EQ(st.forces_bad, 0u);
  EXPECT_EQ(st.last_force.flags & kForceEnable, kForceEnable);
  EXPECT_EQ(st.last_force.handles[0].pitch_torque, 2500);
  EXPECT_EQ(st.last_force.handles[1].insertion_force, -1500);
  // No more commands: the firmware watchdog turns the motors off 2 ms after the last packet.
  for (int i = 0; i < 2000; ++i) {
    const double now = monotonic_s();
    const EmulatedRigStats w = rig.stats();
    if (now - w.last_force_time_s > 2e-3 + 1e-4) {
      ASSERT_FALSE(w.motors_on) << (now - w.last_force_time_s) * 1e3 << " ms after the last packet";
    }
    if (!w.motors_on) break;
  }
  std::this_thread::sleep_for(std::chrono::milliseconds(20));
  const EmulatedRigStats later = rig.stats();
  EXPECT_FALSE(later.motors_on);
  EXPECT_GE(later.watchdog_trips, 1u);
}

TEST(UsbRigEmulated, MalformedPacketsAreRejectedAndCounted) {
  SEROSA_UNDER_UMOCKDEV();
  EmulatedRig rig(rig_config());
  UsbRig usb;
  ASSERT_TRUE(wait_for([&] { return usb.counters().packets >= 20; }, 10.0));
  rig.inject(RigFault::kShortPacket);
  rig.inject(RigFault::kBadChecksum);
  rig.inject(RigFault::kBadVersion);
  ASSERT_TRUE(wait_for(
      [&] {
        const auto n = usb.counters();
        return n.too_short >= 1 && n.bad_checksum >= 1 && n.bad_type_version >= 1;
      },
      10.0));
  const std::uint64_t before = usb.counters().packets;
  ASSERT_TRUE(wait_for([&] { return usb.counters().packets >= before + 20; }, 10.0));
  const UsbRigCounters n = usb.counters();
  EXPECT_EQ(n.too_short, 1u);
  EXPECT_EQ(n.bad_checksum, 1u);
  EXPECT_EQ(n.bad_type_version, 1u);
  EXPECT_GE(n.lost, 3u);  // the three rejected packets show up as sequence gaps
  EXPECT_TRUE(usb.connected());
}

TEST(UsbRigEmulated, StallIsClearedAndStreamingResumes) {
  SEROSA_UNDER_UMOCKDEV();
  EmulatedRig rig(rig_config());
  UsbRig usb;
  ASSERT_TRUE(wait_for([&] { return usb.counters().packets >= 20; }, 10.0));
  rig.inject(RigFault::kStall);
  ASSERT_TRUE(wait_for([&] { return usb.counters().stalls >= 1; }, 10.0));
  ASSERT_TRUE(wait_for([&] { return rig.stats().stalls_cleared >= 1; }, 10.0));
  const std::uint64_t before = usb.counters().packets;
  EXPECT_TRUE(wait_for([&] { return usb.counters().packets >= before + 50; }, 10.0));
  EXPECT_TRUE(usb.connected());
}

TEST(UsbRigEmulated, UnplugAndReplugWithoutRestart) {
  SEROSA_UNDER_UMOCKDEV();
  EmulatedRig rig(rig_config());
  UsbRig usb;
  ASSERT_TRUE(wait_for([&] { return usb.counters().packets >= 20; }, 10.0));
  rig.unplug();
  // The driver clears connected() before it counts the disconnect: wait for both.
  ASSERT_TRUE(wait_for([&] { return !usb.connected() && usb.counters().disconnects >= 1u; }, 5.0));
  const std::uint64_t during = usb.counters().packets;
  std::this_thread::sleep_for(std::chrono::milliseconds(50));
  EXPECT_EQ(usb.counters().packets, during);
  rig.replug();
  ASSERT_TRUE(wait_for([&] { return usb.connected(); }, 5.0));
  EXPECT_TRUE(wait_for([&] { return usb.counters().packets >= during + 50; }, 10.0));
  EXPECT_EQ(usb.counters().connects, 2u);
}

TEST(UsbRigEmulated, RigPluggedInSeesTheRigComeAndGo) {
  SEROSA_UNDER_UMOCKDEV();
  EXPECT_FALSE(rig_plugged_in());  // the testbed holds no device yet
  EmulatedRig rig(rig_config());
  EXPECT_TRUE(rig_plugged_in());
  EXPECT_FALSE(rig_plugged_in(kRigVendorId, kRigProductId + 1));  // another device's ids
  rig.unplug();
  EXPECT_FALSE(rig_plugged_in());
  rig.replug();
  EXPECT_TRUE(rig_plugged_in());
}

TEST(UsbRigEmulated, HapticLoopOverUsbRendersAndZeroesOnUnplug) {
  SEROSA_UNDER_UMOCKDEV();
  EmulatedRig rig(rig_config());
  UsbRig usb;
  ASSERT_TRUE(wait_for([&] { return usb.connected(); }, 5.0));
  // A contact plane just above the tip of handle 0 (pushing it back along -z of the scene).
  const ToolState tip = forward(Trocar{}, test_joints());
  ContactModel m;
  m.step = 1;
  m.tools[0].n_contacts = 1;
  m.tools[0].contacts[0].point_m = {tip.tip_m[0], tip.tip_m[1], tip.tip_m[2] - 0.005};
  m.tools[0].contacts[0].normal = {0.0, 0.0, -1.0};
  m.tools[0].contacts[0].stiffness_Npm = 400.0;  // 2 N
  ContactModelChannel ch(m);
  HapticLoopConfig c;
  c.device_timeout_s = 50e-3;  // the emulated link is slower than real USB (see the docs)
  c.model_timeout_s = 1e9;
  HapticLoop loop(usb, ch, c);
  loop.start();
  ASSERT_TRUE(wait_for([&] { return rig.stats().forces_ok >= 50; }, 10.0));
  ASSERT_TRUE(wait_for([&] { return rig.stats().motors_on; }, 5.0));
  // The tool follows the emulated handle.
  const ToolState ts = loop.tool_state(0).load();
  EXPECT_NEAR(ts.tip_m[2], tip.tip_m[2], 1e-3);
  // The force reached the firmware: insertion effort about -2 N (pushes the tool out).
  const auto f = rig.stats().last_force.handles[0];
  EXPECT_LT(f.insertion_force, -1000);
  EXPECT_GT(f.insertion_force, -2100);
  // Unplug: the loop sees it and renders zero; no force packet reaches the firmware any more, so
  // its watchdog turns the motors off 2 ms after the last one (the loop may see the unplug
  // first: wait a little beyond that, not forever).
  rig.unplug();
  ASSERT_TRUE(wait_for([&] { return loop.status().load().zero_reason != 0; }, 5.0));
  EXPECT_EQ(loop.status().load().enabled, 0u);
  EXPECT_TRUE(wait_for([&] { return !rig.stats().motors_on; }, 0.02));
  // Replug: forces come back without restarting anything.
  rig.replug();
  const std::uint64_t forces = rig.stats().forces_ok;
  ASSERT_TRUE(wait_for([&] { return rig.stats().forces_ok >= forces + 50; }, 10.0));
  EXPECT_TRUE(wait_for([&] { return rig.stats().motors_on; }, 5.0));
  loop.stop();
  EXPECT_FALSE(rig.latencies().empty());
}

}  // namespace
}  // namespace serosa::haptics
