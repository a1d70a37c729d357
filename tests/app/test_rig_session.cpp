// "haptics" with rig tools: a headless run whose two tools (grasper on the left handle, scissors
// on the right) are driven by the unmodified libusb driver (haptics::UsbRig) against the
// umockdev-emulated rig (haptics::EmulatedRig) playing a short tool path. The solver consumes the
// handles' poses (checked in the recording of what it consumed) and the rig's firmware receives
// the loop's force commands. The test re-runs itself under umockdev-wrapper (the preload library
// must be in the process from its start), like tests/haptics/test_usb_rig_emulated.cpp.
#include <gtest/gtest.h>
#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cstdlib>
#include <fstream>
#include <sstream>
#include <string>
#include <thread>
#include <vector>

#include "app/assemble_state.h"
#include "app/compose.h"
#include "app/headless.h"
#include "app_test_util.h"
#include "cutting/validate.h"
#include "engine/instrument_hold.h"
#include "engine/io/mesh_io.h"
#include "engine/scene/scene.h"
#include "engine/scene/tool_path.h"
#include "haptics/emulated_rig.h"
#include "haptics/force_renderer.h"
#include "haptics/haptic_loop.h"
#include "haptics/haptics_stage.h"
#include "haptics/trocar_kinematics.h"
#include "recording/recording_reader.h"
#include "umockdev_rerun.h"
#include "window/overlay_stats.h"

namespace serosa::app {
namespace {

using namespace serosa::app::testing;

using test_support::rerun_under_umockdev;

// Where the tip lies along the segment a -> b: (fraction in [0, 1], distance off it, m).
std::pair<double, double> along(const Vec3& p, const Vec3& a, const Vec3& b) {
  const Vec3 d = b - a;
  const double s = std::clamp((p - a).dot(d) / d.squaredNorm(), 0.0, 1.0);
  return {s, (p - (a + s * d)).norm()};
}

constexpr double kMoveS = 0.4;  // path time of the motion; the handles hold still afterwards
constexpr int kPedal = 2;       // the cautery pedal's bit (docs/rig-protocol.md)

TEST(RigSession, EmulatedRigDrivesBothToolsAndReceivesForces) {
  if (!haptics::umockdev_preload_active()) {
    const int rc = rerun_under_umockdev();
    ASSERT_EQ(rc, 0) << "the test failed under umockdev-wrapper (see its output); "
                        "-2 means umockdev-wrapper was not found";
    return;
  }
  const fs::path dir = out_dir("rig_session");
  std::string toml = "[scene]\ndt = 0.005\neffects = [\"fem\", \"gravity\", \"haptics\"]\n";
  toml.append("[[organ]]\nname = \"beam\"\nmesh = \"")
      .append(source("assets/beam_coarse.msh").string())
      .append("\"\nyoung = 1e5\ndensity = 1000\n")
      .append("fixed = { box = [[-0.001, -1, -1], [0.0001, 1, 1]] }\n")
      .append("[solver]\nkind = \"pcg\"\n")
      // The right-hand tool first: `hand`, not scene order, picks the handle.
      .append("[[tool]]\nname = \"scissors\"\nkind = \"scissors\"\ndevice = \"rig-emulated\"\n")
      .append("hand = \"right\"\ntrocar = [0.07, 0.2, 0.0]\n")
      .append("[[tool]]\nname = \"grasper\"\nkind = \"grasper\"\ndevice = \"rig-emulated\"\n")
      .append("hand = \"left\"\ntrocar = [0.03, 0.2, 0.0]\n");
  std::ofstream(dir / "scene.toml") << toml;

  // The trocars the stage will use (they point at the organs' centroid, as compose aims them).
  const Scene scene = load_scene(dir / "scene.toml");
  const AssembledScene assembled = assemble_state(scene);
  Vec3 aim = Vec3::Zero();
  for (const Vec3& x : assembled.state.mesh.x) aim += x;
  aim /= static_cast<double>(assembled.state.mesh.x.size());
  ASSERT_EQ(scene.tools[1].name, "grasper");
  const std::array<haptics::Trocar, haptics::kHandles> trocars{rig_trocar(scene.tools[1], 0, aim),
                                                               rig_trocar(scene.tools[0], 1, aim)};

  // Each handle moves its tip 1 cm, 2-3 cm above the beam, then holds; the jaw opens meanwhile;
  // the right foot holds the cautery pedal down.
  const std::array<Vec3, 2> from{Vec3(0.03, 0.04, 0.0), Vec3(0.07, 0.035, 0.005)};
  const std::array<Vec3, 2> to{Vec3(0.04, 0.03, 0.0), Vec3(0.06, 0.03, -0.005)};
  const std::array<std::string, 2> names{"grasper", "scissors"};
  std::ostringstream csv;
  csv.precision(17);
  csv << "t,tool,px,py,pz,qw,qx,qy,qz,jaw,buttons\n";
  for (double t : {0.0, kMoveS, 100.0}) {
    const double s = std::min(t / kMoveS, 1.0);
    for (std::size_t h = 0; h < 2; ++h) {
      haptics::JointState q0;
      q0.jaw_rad = 0.5 * s;
      const haptics::JointState q =
          haptics::inverse_from_tip(trocars[h], from[h] + s * (to[h] - from[h]), q0);
      const ToolState p = haptics::forward(trocars[h], q);
      csv << t << ',' << names[h] << ',' << p.tip_m[0] << ',' << p.tip_m[1] << ',' << p.tip_m[2]
          << ',' << p.quat_wxyz[0] << ',' << p.quat_wxyz[1] << ',' << p.quat_wxyz[2] << ','
          << p.quat_wxyz[3] << ',' << p.jaw_rad << ',' << kPedal * h << '\n';  // scissors: pedal
    }
  }
  haptics::EmulatedRigConfig rc;
  rc.path = parse_tool_path_text(csv.str(), "rig_path.csv");
  rc.tool_of_handle = {rc.path.index_of("grasper"), rc.path.index_of("scissors")};
  rc.trocars = trocars;
  haptics::EmulatedRig rig(rc);  // before the driver's libusb context (the stage's)
  // Let the handles get under way, so the run sees them move rather than sit at the start.
  std::this_thread::sleep_for(std::chrono::milliseconds(50));

  HeadlessOptions o;
  o.scene = dir / "scene.toml";
  o.steps = 150;
  o.record = dir / "run.lapr";
  o.progress = false;
  const auto report = run_headless(o);
  ASSERT_TRUE(report.contains("haptics")) << report.dump(1);
  const auto& hj = report["haptics"];
  EXPECT_EQ(hj["device"], "rig-emulated");
  EXPECT_TRUE(hj["device_connected"].get<bool>()) << hj.dump(1);
  EXPECT_GT(hj["rig"]["packets"].get<std::uint64_t>(), 0u);
  EXPECT_EQ(hj["rig"]["rejected"].get<std::uint64_t>(), 0u);
  EXPECT_GT(hj["rig"]["commands_sent"].get<std::uint64_t>(), 0u);

  // The firmware decoded the loop's force commands, none malformed.
  const haptics::EmulatedRigStats st = rig.stats();
  EXPECT_GE(st.forces_ok, 10u);
  EXPECT_EQ(st.forces_bad, 0u);

  // What the solver consumed: each tool's tip on its handle's path, moving forward along it
  // (never back), with the jaw the path gives at that point.
  const recording::Recording rec = recording::read_recording(*o.record);
  ASSERT_EQ(rec.inputs.size(), 150u);
  const std::array<std::size_t, 2> tool_of_handle{1, 0};  // scene order: scissors, grasper
  std::size_t driven = 0;
  double max_progress = 0.0;
  std::array<double, 2> last{0.0, 0.0};
  for (std::size_t k = 0; k < rec.inputs.size(); ++k) {
    for (std::size_t h = 0; h < 2; ++h) {
      const ToolState& t = rec.inputs[k][tool_of_handle[h]];
      if (t.tick == 0) continue;  // before the loop's first sample
      ++driven;
      const Vec3 tip(t.tip_m[0], t.tip_m[1], t.tip_m[2]);
      const auto [s, off] = along(tip, from[h], to[h]);
      EXPECT_LT(off, 5e-4) << "step " << k << " handle " << h;
      EXPECT_GE(s, last[h] - 0.02) << "step " << k << " handle " << h << " went back";
      EXPECT_NEAR(t.jaw_rad, 0.5 * s, 0.02) << "step " << k << " handle " << h;
      EXPECT_EQ(t.buttons & kDeviceButtons, static_cast<std::uint32_t>(kPedal * h))
          << "step " << k;  // pedal too
      EXPECT_EQ(holder(t), h == 0 ? Hand::kLeft : Hand::kRight) << "step " << k;
      last[h] = std::max(last[h], s);
      max_progress = std::max(max_progress, s);
    }
  }
  EXPECT_GE(driven, 2u * 100u) << "most steps should consume the rig's poses";
  EXPECT_GT(max_progress, 0.1) << "the tools should have moved along the path";
}

// The whole rig path from the command line, as CI runs it: `serosa headless` on the bundled rig
// scene re-runs itself under umockdev-wrapper, emulates the rig whose two handles play the whole
// appendectomy as a trainee's hands would (the right hand exchanging its instrument four times
// through the handle button), steps in real time, and completes the procedure.
TEST(RigSession, TheRigScenePerformsTheWholeAppendectomyThroughTheEmulatedRig) {
  const fs::path dir = out_dir("rig_scene");
  const CliResult r =
      run_serosa("headless '" + source("config/appendectomy_rig.toml").string() + "' --report '" +
                 (dir / "report.json").string() + "' --export-final '" +
                 (dir / "final.msh").string() + "' > /dev/null");
  ASSERT_EQ(r.code, 0) << r.out;
  std::ifstream in(dir / "report.json");
  const nlohmann::json report = nlohmann::json::parse(in);
  EXPECT_TRUE(report["paced_to_real_time"].get<bool>());
  const auto& hj = report["haptics"];
  EXPECT_EQ(hj["device"], "rig-emulated");
  EXPECT_TRUE(hj["device_connected"].get<bool>()) << hj.dump(1);
  const auto& rig = hj["rig"];
  EXPECT_EQ(rig["rejected"].get<std::uint64_t>(), 0u);
  EXPECT_EQ(rig["lost"].get<std::uint64_t>(), 0u);
  // A packet each millisecond of wall time, and the run never gets ahead of real time. The loop
  // is a plain thread here (no real-time priority in CI): on a busy two-core runner it was seen
  // to lose a tenth of its ticks, so the floor is three quarters of the rate: a loop that stalled
  // or ran at the solver's pace would be far below it.
  const double packets = rig["packets"].get<double>();
  EXPECT_GE(packets, 750.0 * report["simulated_time_s"].get<double>()) << rig.dump(1);
  EXPECT_LT(packets, 1000.0 * report["wall_time_s"].get<double>() + 50.0) << rig.dump(1);
  // The force commands reached the emulated firmware, none malformed.
  EXPECT_GT(rig["emulated"]["forces_ok"].get<double>(), 0.5 * packets);
  EXPECT_EQ(rig["emulated"]["forces_bad"].get<std::uint64_t>(), 0u);
  // The procedure, done by the two handles: five steps, the right hand's four exchanges.
  const auto& proc = report["procedure"];
  EXPECT_TRUE(proc["completed"].get<bool>()) << proc.dump(1);
  for (const auto& step : proc["steps"]) EXPECT_TRUE(step["done"].get<bool>()) << step.dump();
  EXPECT_EQ(proc["steps"].size(), 5u);
  EXPECT_GE(proc["specimen_volume_fraction"].get<double>(), 0.8);
  const auto& exchanges = report["metrics"]["exchanges"];
  const std::vector<std::string> taken = {"clip-applier", "hook", "endoloop", "scissors"};
  ASSERT_EQ(exchanges.size(), taken.size()) << exchanges.dump(1);
  for (std::size_t k = 0; k < taken.size(); ++k) {
    EXPECT_EQ(exchanges[k]["hand"], "right");
    EXPECT_EQ(exchanges[k]["to"], taken[k]);
    EXPECT_EQ(exchanges[k]["from"], k == 0 ? "scissors" : taken[k - 1]);
  }
  // Each instrument's forces went to the handle that held it: every instrument that loaded the
  // tissue (its tip force in the report) turned its hand's handle.
  const auto& efforts = rig["emulated"]["efforts"];
  EXPECT_TRUE(efforts["left"].contains("grasper")) << efforts.dump(1);
  for (const std::string& tool : taken)
    EXPECT_TRUE(efforts["right"].contains(tool)) << efforts.dump(1);
  for (const auto& [tool, force] : report["metrics"]["force_max_n"].items()) {
    if (force.get<double>() < 0.1) continue;
    const char* hand = tool == "grasper" ? "left" : "right";
    EXPECT_GT(efforts[hand][tool]["peak_torque_nm"].get<double>(), 1e-3) << tool;
  }
  // Every cut reached the loop as a force event within the slew limits; the transection's also
  // in the scissors' jaw torque (the appendix between the blades).
  int cut_events = 0;
  double last_jaw_step = 0.0;
  for (const auto& e : hj["force_events"]) {
    if (!(e["kind"].get<int>() & 1)) continue;
    ++cut_events;
    last_jaw_step = e["max_jaw_step_Nm"].get<double>();
    EXPECT_LE(e["max_jaw_step_Nm"].get<double>(),
              haptics::ForceRendererParams{}.jaw_slew_Nm_per_s * 2e-3);
    EXPECT_LE(e["max_step_N"].get<double>(), haptics::ForceRendererParams{}.slew_N_per_s * 2e-3);
  }
  EXPECT_GE(cut_events, 1) << hj["force_events"].dump(1);
  EXPECT_GT(last_jaw_step, 0.0) << hj["force_events"].dump(1);
  EXPECT_TRUE(report["mesh_final"]["valid"].get<bool>());
}

// Unplugging the rig mid-session: the loop renders zero and the overlay says "disconnected" (not
// "not connected", as for a rig never seen); plugged back in, the session goes on with it.
TEST(RigSession, UnplugMidSessionIsToldApartAndAReplugResumes) {
  if (!haptics::umockdev_preload_active()) {
    ASSERT_EQ(rerun_under_umockdev(), 0) << "the test failed under umockdev-wrapper";
    return;
  }
  const fs::path dir = out_dir("rig_unplug");
  std::ofstream(dir / "path.csv") << "t,tool,px,py,pz,qw,qx,qy,qz,jaw\n"
                                  << "0,grasper,0.05,0.03,0.0,1,0,0,0,0.3\n";
  std::string toml = "[scene]\ndt = 0.005\neffects = [\"fem\", \"haptics\"]\n";
  toml.append("[[organ]]\nname = \"beam\"\nmesh = \"")
      .append(source("assets/beam_coarse.msh").string())
      .append("\"\nyoung = 1e5\ndensity = 1000\n")
      .append("[[tool]]\nname = \"grasper\"\nkind = \"grasper\"\n")
      .append("device = \"rig-emulated:path.csv\"\nhand = \"left\"\ntrocar = [0.05, 0.2, 0.0]\n");
  std::ofstream(dir / "scene.toml") << toml;
  const Scene scene = load_scene(dir / "scene.toml");
  haptics::HapticsStage stage(scene, haptics::HapticsStageOptions{});
  ASSERT_TRUE(stage.device_connected());
  SimState s;
  s.tools.resize(1);
  s.events.tool_reactions.resize(1);
  s.events.tool_reactions[0].held_pull_n = Vec3(0.0, -0.5, 0.0);  // held tissue pulls down
  std::uint64_t step = 0;
  const auto run_for = [&](double seconds) {
    const auto end = std::chrono::steady_clock::now() + std::chrono::duration<double>(seconds);
    while (std::chrono::steady_clock::now() < end) {
      stage.step(StepContext{step, 0.005 * static_cast<double>(step), 0.005}, s);
      ++step;
      std::this_thread::sleep_for(std::chrono::milliseconds(5));
    }
  };
  const auto label = [&] {
    return std::string(window::instruments_label(stage.device_kind(), stage.device_connected(),
                                                 false, stage.rig_was_connected()));
  };
  // Connected, the held tissue's pull reaches the hand (after the slew ramp, and again after any
  // late tick of a loaded or sanitizer build zeroed it: wait until it shows, at most 10 s).
  const auto pulls = [&] {
    return label() == "emulated rig" &&
           std::abs(std::abs(stage.status().tip_force_N[0][1]) - 0.5) < 1e-9;
  };
  const auto wait_until = [&](const auto& what) {
    const auto end = std::chrono::steady_clock::now() + std::chrono::seconds(10);
    while (!what() && std::chrono::steady_clock::now() < end) run_for(0.02);
    return what();
  };
  EXPECT_TRUE(wait_until(pulls)) << label() << ", force " << stage.status().tip_force_N[0][1];
  ASSERT_TRUE(stage.emulated_rig() != nullptr);
  stage.emulated_rig()->unplug();
  // The loop notices on its next failed transfer; a sanitizer build on a loaded machine can take
  // longer than the firmware's watchdog to get there, so wait for it (at most 10 s).
  EXPECT_TRUE(wait_until([&] { return !stage.device_connected(); }));
  run_for(0.05);
  EXPECT_FALSE(stage.device_connected());
  EXPECT_EQ(label(), "emulated rig disconnected");
  EXPECT_EQ(stage.status().enabled, 0u);
  EXPECT_EQ(stage.status().tip_force_N[0][1], 0.0);
  // Plugged back: the driver reopens it (hotplug, or its retry every 0.5 s) and the pull is back.
  stage.emulated_rig()->replug();
  EXPECT_TRUE(wait_until(pulls)) << label() << ", force " << stage.status().tip_force_N[0][1];
}

TEST(RigSession, AbsentRigStartsTheRunAndSaysNotConnected) {
  // No EmulatedRig and no preload: libusb finds no rig. The run must start, keep the tool still,
  // and report the rig as not connected (with the ticks it spent so).
  const fs::path dir = out_dir("rig_absent");
  std::string toml = "[scene]\ndt = 0.005\neffects = [\"fem\", \"gravity\", \"haptics\"]\n";
  toml.append("[[organ]]\nname = \"beam\"\nmesh = \"")
      .append(source("assets/beam_coarse.msh").string())
      .append("\"\nyoung = 1e5\ndensity = 1000\n")
      .append("fixed = { box = [[-0.001, -1, -1], [0.0001, 1, 1]] }\n")
      .append("[solver]\nkind = \"pcg\"\n")
      .append("[[tool]]\nname = \"grasper\"\nkind = \"grasper\"\ndevice = \"rig\"\n")
      .append("hand = \"left\"\ntrocar = [0.03, 0.2, 0.0]\n");
  std::ofstream(dir / "scene.toml") << toml;
  HeadlessOptions o;
  o.scene = dir / "scene.toml";
  o.steps = 100;
  o.progress = false;
  nlohmann::json report;
  ASSERT_NO_THROW(report = run_headless(o));
  EXPECT_EQ(report["steps_taken"], 100);
  const auto& hj = report["haptics"];
  EXPECT_EQ(hj["device"], "rig");
  EXPECT_FALSE(hj["device_connected"].get<bool>());
  EXPECT_FALSE(hj["rig"]["connected"].get<bool>());
  EXPECT_EQ(hj["rig"]["packets"], 0u);
  EXPECT_GT(hj["rig"]["not_connected_ticks"].get<std::uint64_t>(), 0u) << hj.dump(1);
}

}  // namespace
}  // namespace serosa::app
