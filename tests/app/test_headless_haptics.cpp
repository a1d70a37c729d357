// "haptics" in a headless run: the 1 kHz loop runs beside the solver with a scripted device, the
// solver consumes the loop's tool states at step boundaries, the report carries the loop's
// telemetry, and the recording of what the solver consumed replays --verify bit for bit.
#include <gtest/gtest.h>

#include <fstream>

#include "app/headless.h"
#include "app_test_util.h"
#include "recording/recording_reader.h"
#include "replay/replay.h"

namespace serosa::app {
namespace {

using namespace serosa::replay;

using namespace serosa::app::testing;

TEST(HeadlessHaptics, LoopRunsBesideTheSolverAndTheRecordingReplaysBitForBit) {
  const fs::path dir = out_dir("headless_haptics");
  // A grasper moving 2 cm above the beam over 2 s (real time, played by the device).
  std::ofstream(dir / "path.csv")
      << "t,tool,px,py,pz,qw,qx,qy,qz,jaw\n"
         "0,grasper,0.05,0.03,0,0.7071067811865476,0.7071067811865476,0,0,0\n"
         "2,grasper,0.07,0.03,0,0.7071067811865476,0.7071067811865476,0,0,0.5\n";
  std::string toml = "[scene]\ndt = 0.005\neffects = [\"fem\", \"gravity\", \"haptics\"]\n";
  toml.append("[[organ]]\nname = \"beam\"\nmesh = \"")
      .append(source("assets/beam_coarse.msh").string())
      .append("\"\nyoung = 1e5\ndensity = 1000\n")
      .append("fixed = { box = [[-0.001, -1, -1], [0.0001, 1, 1]] }\n")
      .append("[solver]\nkind = \"pcg\"\n[record]\nhash_every = 10\n")
      .append("[[tool]]\nname = \"grasper\"\nkind = \"grasper\"\ndevice = \"script:path.csv\"\n")
      .append("trocar = [0.05, 0.2, 0.0]\n");
  std::ofstream(dir / "scene.toml") << toml;

  HeadlessOptions o;
  o.scene = dir / "scene.toml";
  o.steps = 200;
  o.record = dir / "run.lapr";
  o.progress = false;
  const auto report = run_headless(o);
  ASSERT_TRUE(report.contains("haptics")) << report.dump(1);
  EXPECT_GT(report["haptics"]["ticks"].get<std::uint64_t>(), 0u) << report["haptics"].dump(1);
  bool simulated = false;
  for (const auto& e : report["effects"]["simulated"]) simulated = simulated || e == "haptics";
  EXPECT_TRUE(simulated);

  // The solver consumed the loop's states (they carry its tick), and recorded them.
  const recording::Recording rec = recording::read_recording(*o.record);
  ASSERT_EQ(rec.inputs.size(), 200u);
  EXPECT_GT(rec.inputs.back()[0].tick, 0u);

  // Replay feeds those inputs back without the loop: bit for bit.
  ReplayOptions ro;
  ro.recording = *o.record;
  ro.verify = true;
  ro.progress = false;
  const ReplayResult r = run_replay(ro);
  EXPECT_EQ(r.steps, 200u);
  EXPECT_EQ(r.hashes_checked, 20u);
  EXPECT_FALSE(r.diverged_at.has_value());
  EXPECT_EQ(r.report["state_hash"], report["state_hash"]);
}

}  // namespace
}  // namespace serosa::app
