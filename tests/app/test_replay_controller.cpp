// The replay window's core without a window (replay/replay_controller.h): play, pause, speed and
// seek over a recorded scripted transection (cuts included). Exact seeks land on the recorded
// state hashes, backwards equals forwards; snapshot seeks are bit-exact at the snapshot and stay
// close after it.
#include <gtest/gtest.h>

#include <sys/wait.h>

#include <array>
#include <cstdio>
#include <fstream>
#include <map>

#include "app/headless.h"
#include "app_test_util.h"
#include "engine/input_error.h"
#include "replay/replay.h"
#include "replay/replay_controller.h"
#include "support/test_paths.h"

namespace serosa::app {
namespace {

using namespace serosa::replay;

using namespace serosa::app::testing;

constexpr std::int64_t kSteps = 40;  // hashes recorded after steps 19 and 39 (hash_every 20)

// Records the scripted transection once per test process.
const fs::path& recording() {
  static const fs::path file = [] {
    const fs::path dir = own_dir("replay_controller");
    HeadlessOptions o;
    o.scene = source("config/transection.toml");
    o.tool_path = source("config/paths/appendix_transection.csv");
    o.steps = kSteps;
    o.record = dir / "run.lapr";
    o.progress = false;
    const auto report = run_headless(o);
    EXPECT_GT(report["cutting"]["cuts"].get<int>(), 0);
    return *o.record;
  }();
  return file;
}

// The hash after each step of a plain forward replay: steps taken -> last_step_hash().
const std::map<std::uint64_t, std::uint64_t>& forward_hashes() {
  static const std::map<std::uint64_t, std::uint64_t> hashes = [] {
    ReplayController c(recording());
    std::map<std::uint64_t, std::uint64_t> h;
    while (c.step_forward()) h[c.steps_taken()] = *c.last_step_hash();
    EXPECT_EQ(c.hashes_checked(), 2u);
    EXPECT_FALSE(c.diverged_at().has_value());
    return h;
  }();
  return hashes;
}

// A 40-step recording of the beam (FEM only, no tools): cheap, for pacing.
const fs::path& beam_recording() {
  static const fs::path file = [] {
    const fs::path dir = own_dir("replay_controller_beam");
    HeadlessOptions o;
    o.scene = source("config/beam.toml");
    o.steps = kSteps;
    o.record = dir / "beam.lapr";
    o.progress = false;
    (void)run_headless(o);
    return *o.record;
  }();
  return file;
}

TEST(ReplayController, ExactSeekLandsOnTheRecordedHashesBackwardsAndForwards) {
  const auto& fwd = forward_hashes();
  ASSERT_EQ(fwd.size(), static_cast<std::size_t>(kSteps));
  ReplayControllerOptions o;
  o.snapshot_every_s = 0.05;  // 10 steps
  ReplayController c(recording(), o);
  EXPECT_EQ(c.num_steps(), 40u);
  EXPECT_NEAR(c.duration_s(), 0.2, 1e-12);
  const auto& rec = c.recording().hashes;

  // Forward to t = 0.1 s: the state after 20 steps, hashed as the recorder did after step 19.
  c.seek(0.1);
  EXPECT_EQ(c.steps_taken(), 20u);
  ASSERT_TRUE(c.last_step_hash().has_value());
  EXPECT_EQ(*c.last_step_hash(), rec.at(19));
  // To the end, then back to 20 and to 7: the same hashes as going forward.
  c.seek_step(40);
  EXPECT_EQ(*c.last_step_hash(), rec.at(39));
  EXPECT_TRUE(c.at_end());
  c.seek_step(7);
  EXPECT_EQ(*c.last_step_hash(), fwd.at(7));
  EXPECT_TRUE(c.exact());
  // Every step after a backward seek matches the forward pass (through the cuts).
  while (c.steps_taken() < 25 && c.step_forward())
    ASSERT_EQ(*c.last_step_hash(), fwd.at(c.steps_taken()));
  EXPECT_FALSE(c.diverged_at().has_value());
  // Clamped: past the end, before the start.
  c.seek(99.0);
  EXPECT_EQ(c.steps_taken(), 40u);
  c.seek(-1.0);
  EXPECT_EQ(c.steps_taken(), 0u);
  EXPECT_FALSE(c.last_step_hash().has_value());
}

TEST(ReplayController, SnapshotSeekRestoresTheWholeStateBitForBit) {
  const auto& fwd = forward_hashes();
  ReplayControllerOptions o;
  o.snapshot_every_s = 0.05;  // 10 steps
  ReplayController c(recording(), o);
  c.seek_step(40);
  // 10, 20, 30, 40, less any step with a cut still in flight (the FEM takes it at the next).
  EXPECT_GE(c.num_snapshots(), 2u);
  EXPECT_LE(c.num_snapshots(), 4u);
  const std::uint64_t hash40 = *c.last_step_hash();
  const std::uint64_t restarts = c.restarts();

  // Back to 35: restored from the snapshot at or before it, no re-simulation from the start;
  // every later step's hash equals the forward run's (warm starts, factor schedule, strokes and
  // grasps came back with it).
  c.seek_step(35);
  EXPECT_EQ(c.restarts(), restarts + 1);
  EXPECT_EQ(c.steps_taken(), 35u);
  EXPECT_EQ(*c.last_step_hash(), fwd.at(35));
  EXPECT_TRUE(c.exact());
  while (c.step_forward()) ASSERT_EQ(*c.last_step_hash(), fwd.at(c.steps_taken()));
  EXPECT_EQ(*c.last_step_hash(), hash40);
  EXPECT_FALSE(c.diverged_at().has_value());

  // from_start: the same states by re-simulating from step 0.
  ReplayControllerOptions slow = o;
  slow.from_start = true;
  ReplayController d(recording(), slow);
  d.seek_step(40);
  d.seek_step(35);
  EXPECT_EQ(*d.last_step_hash(), fwd.at(35));
  EXPECT_EQ(d.restarts(), 2u);
}

TEST(ReplayController, PauseAndSpeedPaceThePlayback) {
  ReplayController c(beam_recording());
  const double dt = c.dt_s();
  // 1x: 10 dt of wall time take 10 steps (in pieces of 0.4 dt: no step is lost to rounding).
  for (int i = 0; i < 25; ++i) c.advance(0.4 * dt);
  EXPECT_EQ(c.steps_taken(), 10u);
  // Paused: nothing moves.
  c.set_paused(true);
  EXPECT_EQ(c.advance(10.0 * dt), 0u);
  EXPECT_EQ(c.steps_taken(), 10u);
  c.set_paused(false);
  // 2x: 5 dt of wall time take 10 steps; 0.5x: 10 dt take 5.
  c.set_speed(2.0);
  EXPECT_EQ(c.advance(5.0 * dt + 1e-9), 10u);
  c.set_speed(0.5);
  EXPECT_EQ(c.advance(10.0 * dt + 1e-9), 5u);
  EXPECT_EQ(c.steps_taken(), 25u);
  // Speeds are clamped; the end stops playback.
  c.set_speed(1000.0);
  EXPECT_EQ(c.speed(), ReplayController::kMaxSpeed);
  c.set_speed(0.0);
  EXPECT_EQ(c.speed(), ReplayController::kMinSpeed);
  c.set_speed(16.0);
  EXPECT_EQ(c.advance(100.0), 15u);
  EXPECT_TRUE(c.at_end());
  EXPECT_EQ(c.advance(1.0), 0u);
}

TEST(ReplayController, NotARecordingIsAClearError) {
  const fs::path dir = out_dir("replay_controller_bad");
  std::ofstream(dir / "bad.lapr") << "not a recording";
  EXPECT_THROW(ReplayController c(dir / "bad.lapr"), InputError);
}

// Branch from replay: pause at step 10, take over (the scissors stay open instead of closing),
// record the branch; the branch file replays --verify from step 0 with every hash matching, its
// header names the parent and the step, and it really differs from the parent.
TEST(ReplayController, BranchRecordsAFileThatReplaysVerified) {
  const fs::path dir = out_dir("replay_branch");
  ReplayController c(recording());
  c.seek_step(10);
  c.set_paused(true);
  const fs::path file = dir / "branch.lapr";
  c.branch(file);
  EXPECT_TRUE(c.branched());
  EXPECT_EQ(c.branch_step(), 10u);
  EXPECT_THROW(c.branch(dir / "again.lapr"), std::logic_error);
  std::size_t scissors = 0;
  for (std::size_t i = 0; i < c.scene().tools.size(); ++i)
    if (c.scene().tools[i].kind == ToolKind::kScissors) scissors = i;
  ToolState open = c.state().tools[scissors];
  open.jaw_rad = 1.0;
  c.set_tool_input(scissors, open);
  EXPECT_THROW(c.set_tool_input(99, open), std::out_of_range);
  c.set_paused(false);
  for (int i = 0; i < 15; ++i) ASSERT_TRUE(c.step_forward());
  c.seek_step(0);  // refused in a branch
  EXPECT_EQ(c.steps_taken(), 25u);
  const std::uint64_t branch_hash = state_hash(c.state());
  c.end_branch();
  EXPECT_TRUE(c.at_end());
  EXPECT_FALSE(c.step_forward());

  const recording::Recording b = recording::read_recording(file);
  EXPECT_TRUE(b.complete);
  EXPECT_EQ(b.inputs.size(), 25u);
  EXPECT_EQ(b.header.get("branch_step"), "10");
  EXPECT_EQ(b.header.get("parent"), fs::absolute(recording()).lexically_normal().string());
  ASSERT_EQ(b.events.size(), 1u);
  EXPECT_EQ(b.events[0].first, 10u);
  EXPECT_EQ(b.events[0].second, "branch");
  ASSERT_EQ(b.hashes.count(19), 1u);
  const auto& parent = c.recording();
  EXPECT_NE(b.hashes.at(19), parent.hashes.at(19));  // the branch did not cut like the parent

  ReplayOptions o;
  o.recording = file;
  o.verify = true;
  o.progress = false;
  const ReplayResult r = run_replay(o);
  EXPECT_EQ(r.steps, 25u);
  EXPECT_EQ(r.hashes_checked, 1u);
  EXPECT_FALSE(r.diverged_at.has_value());
  EXPECT_EQ(r.report["state_hash"], hash_hex(branch_hash));
}

// `serosa replay REC.lapr` (no --headless) opens a window on a virtual X display, plays and
// closes by itself, leaving its last picture (scene, tools, overlay timeline) as a PNG.
TEST(ReplayWindow, PlaysInAWindowUnderXvfb) {
  const fs::path png =
      fs::path(::serosa::test_paths::binary_dir()) / "test-output" / "render" / "replay_window.png";
  fs::remove(png);
  const std::string cmd = "xvfb-run -a -s '-screen 0 1280x720x24' '" + serosa_exe().string() +
                          "' replay '" + recording().string() + "' --seconds 2 --speed 0.5 " +
                          "--snapshot '" + png.string() + "' 2>&1";
  FILE* pipe = popen(cmd.c_str(), "r");
  ASSERT_NE(pipe, nullptr);
  std::string out;
  std::array<char, 4096> buf{};
  std::size_t n = 0;
  while ((n = std::fread(buf.data(), 1, buf.size(), pipe)) > 0) out.append(buf.data(), n);
  const int status = pclose(pipe);
  ASSERT_TRUE(WIFEXITED(status)) << out;
  EXPECT_EQ(WEXITSTATUS(status), 0) << out;
  EXPECT_NE(out.find("steps shown"), std::string::npos) << out;
  ASSERT_TRUE(fs::exists(png)) << out;
  EXPECT_GT(fs::file_size(png), 10000u);
}

// Without a display the window cannot open: a clear error, exit 1.
TEST(ReplayWindow, NoDisplayIsAClearError) {
  const std::string cmd = "env -u DISPLAY -u WAYLAND_DISPLAY '" + serosa_exe().string() +
                          "' replay '" + recording().string() + "' 2>&1";
  FILE* pipe = popen(cmd.c_str(), "r");
  ASSERT_NE(pipe, nullptr);
  std::string out;
  std::array<char, 4096> buf{};
  std::size_t n = 0;
  while ((n = std::fread(buf.data(), 1, buf.size(), pipe)) > 0) out.append(buf.data(), n);
  const int status = pclose(pipe);
  EXPECT_EQ(WEXITSTATUS(status), 1) << out;
  EXPECT_NE(out.find("needs a display"), std::string::npos) << out;
}

}  // namespace
}  // namespace serosa::app
