// Replay and branching an instructor can trust: a branch recording carries whole-state snapshots
// at the recording's cadence and starts late from them to the same bits as from step 0; the tools
// no one took over go on as recorded; --from past the end says so, and stdout then holds the
// report alone; the mouse can take over every instrument of the scene (replay/mouse_takeover.h),
// and the branch's line on screen says who drives what (replay/branch_banner.h).
#include <gtest/gtest.h>

#include <algorithm>
#include <fstream>
#include <set>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "app/headless.h"
#include "app_test_util.h"
#include "engine/hook.h"
#include "engine/instrument_hold.h"
#include "engine/scene/tool_path.h"
#include "engine/shell_command.h"
#include "engine/sim_state.h"
#include "recording/recording_reader.h"
#include "replay/branch_banner.h"
#include "replay/mouse_takeover.h"
#include "replay/replay.h"
#include "replay/replay_controller.h"
#include "window/pointer_control.h"

namespace serosa::app {
namespace {

using namespace serosa::replay;

using namespace serosa::app::testing;

constexpr std::int64_t kSteps = 40;  // 0.2 s of the scripted transection
constexpr double kDt = 0.005;

// `text` with `from` replaced by `to` everywhere.
std::string replaced(std::string text, const std::string& from, const std::string& to) {
  for (std::size_t at = text.find(from); at != std::string::npos;
       at = text.find(from, at + to.size()))
    text.replace(at, from.size(), to);
  return text;
}

// The scripted transection with a snapshot every 10 steps (0.05 s), recorded once per process.
// The cadence is the scene file's (a replay rebuilds the scene from the text in the header).
const fs::path& recording() {
  static const fs::path file = [] {
    const fs::path dir = own_dir("branch_replay");
    std::string text = file_text(source("config/transection.toml"));
    text = replaced(text, "\"../assets/", "\"" + source("assets").string() + "/");
    text = replaced(text, "script:paths/", "script:" + source("config/paths").string() + "/");
    text = replaced(text, "\"assessment/", "\"" + source("config/assessment").string() + "/");
    text = replaced(text, "[record]\n", "[record]\nsnapshot_every_s = 0.05\n");
    std::ofstream(dir / "transection.toml") << text;
    HeadlessOptions o;
    o.scene = dir / "transection.toml";
    o.steps = kSteps;
    o.record = dir / "run.lapr";
    o.progress = false;
    (void)run_headless(o);
    return *o.record;
  }();
  return file;
}

std::size_t tool_of(const Scene& scene, ToolKind kind) {
  for (std::size_t i = 0; i < scene.tools.size(); ++i)
    if (scene.tools[i].kind == kind) return i;
  ADD_FAILURE() << "no such tool";
  return 0;
}

// Field by field (the struct has padding).
bool same(const ToolState& a, const ToolState& b) {
  return a.tick == b.tick && a.time_s == b.time_s && a.tip_m == b.tip_m &&
         a.quat_wxyz == b.quat_wxyz && a.jaw_rad == b.jaw_rad && a.buttons == b.buttons;
}

Vec3 tip_of(const ToolState& t) { return Vec3(t.tip_m[0], t.tip_m[1], t.tip_m[2]); }

// Branch at step 15 with the scissors held open, on past the parent's end to step 50: the branch
// file holds the parent's snapshots up to the branch and its own at the cadence after it; --from
// restores one of its own (fewer steps re-simulated than since the branch) and ends on the state
// the branch ended on, as a replay from step 0 does, every snapshot compared whole on the way.
TEST(BranchReplay, TheBranchWritesSnapshotsAndStartsLateFromThem) {
  const fs::path file = own_dir("branch_snapshots") / "branch.lapr";
  ReplayController c(recording());
  c.seek_step(15);
  c.branch(file);
  const std::size_t scissors = tool_of(c.scene(), ToolKind::kScissors);
  ToolState open = c.state().tools[scissors];
  open.jaw_rad = 1.0;
  c.set_tool_input(scissors, open);
  while (c.steps_taken() < 50) ASSERT_TRUE(c.step_forward());
  const std::uint64_t branch_hash = state_hash(c.state());
  c.end_branch();

  const recording::Recording parent = recording::read_recording(recording());
  const recording::Recording b = recording::read_recording(file);
  ASSERT_EQ(b.inputs.size(), 50u);
  std::size_t own = 0;
  for (const auto& [steps, bytes] : b.snapshots) {
    if (steps <= 15) {
      ASSERT_TRUE(parent.snapshots.contains(steps)) << steps;
      EXPECT_TRUE(bytes == parent.snapshots.at(steps)) << steps;
      continue;
    }
    ++own;
    EXPECT_LE(steps % 10, 3u) << steps;  // on the cadence, or a few steps late after a cut
  }
  EXPECT_GE(own, 3u);  // 20, 30, 40, 50, less any step with a cut in flight

  ReplayOptions late;
  late.recording = file;
  late.verify = true;
  late.progress = false;
  late.from_s = 48 * kDt;
  const ReplayResult r = run_replay(late);
  EXPECT_GT(r.start_step, 15u);  // a snapshot the branch wrote
  EXPECT_LE(r.start_step, 48u);
  EXPECT_EQ(r.report["start_step"], r.start_step);
  EXPECT_LT(r.steps, 50u - 15u);
  EXPECT_EQ(r.start_step + r.steps, 50u);
  EXPECT_FALSE(r.diverged_at.has_value());
  EXPECT_EQ(r.report["state_hash"], hash_hex(branch_hash));

  ReplayOptions whole = late;
  whole.from_s.reset();
  const ReplayResult z = run_replay(whole);
  EXPECT_EQ(z.start_step, 0u);
  EXPECT_EQ(z.steps, 50u);
  EXPECT_EQ(z.snapshots_checked, b.snapshots.size());
  EXPECT_FALSE(z.snapshot_diverged_at.has_value()) << z.snapshot_part;
  EXPECT_FALSE(z.diverged_at.has_value());
  EXPECT_EQ(z.report["state_hash"], r.report["state_hash"]);
}

// Only the scissors are taken over: the grasper and the endoscope go on as recorded to the
// recording's end, then hold its last input.
TEST(BranchReplay, ToolsNoOneTookOverGoOnAsRecorded) {
  const fs::path file = own_dir("branch_rest") / "branch.lapr";
  ReplayController c(recording());
  c.seek_step(10);
  EXPECT_TRUE(c.recording_drives(0));
  c.branch(file);
  const std::size_t scissors = tool_of(c.scene(), ToolKind::kScissors);
  const std::size_t grasper = tool_of(c.scene(), ToolKind::kGrasper);
  const std::size_t scope = tool_of(c.scene(), ToolKind::kEndoscope);
  c.set_tool_input(scissors, c.state().tools[scissors]);
  EXPECT_FALSE(c.recording_drives(scissors));
  EXPECT_TRUE(c.recording_drives(grasper));
  const auto& rec = c.recording().inputs;
  while (c.steps_taken() < 45) {
    const std::uint64_t k = c.steps_taken();
    ASSERT_TRUE(c.step_forward());
    const std::vector<ToolState>& want = rec[std::min<std::uint64_t>(k, rec.size() - 1)];
    EXPECT_TRUE(same(c.state().tools[grasper], want[grasper])) << k;
    EXPECT_TRUE(same(c.state().tools[scope], want[scope])) << k;
  }
  c.end_branch();
  ReplayOptions o;
  o.recording = file;
  o.verify = true;
  o.progress = false;
  EXPECT_FALSE(run_replay(o).diverged_at.has_value());
}

// --from after the recording's end: a warning naming the time asked and the recording's length,
// in the report and on stderr; the replay starts from the last snapshot as before. stdout holds
// the report and nothing else, also when the log says there is no snapshot that early.
TEST(BranchReplay, FromPastTheEndWarnsAndStdoutIsTheReportAlone) {
  ReplayOptions o;
  o.recording = recording();
  o.progress = false;
  o.from_s = 50.0;
  const ReplayResult r = run_replay(o);
  const recording::Recording rec = recording::read_recording(recording());
  ASSERT_FALSE(rec.snapshots.empty());
  EXPECT_EQ(r.start_step, rec.snapshots.rbegin()->first);
  ASSERT_EQ(r.report["warnings"].size(), 1u) << r.report["warnings"].dump(1);
  EXPECT_EQ(r.report["warnings"][0]["kind"], "from_past_end");
  const std::string text = r.report["warnings"][0]["text"];
  EXPECT_NE(text.find("--from 50 s is past the end"), std::string::npos) << text;
  EXPECT_NE(text.find("lasts 0.2 s (40 steps)"), std::string::npos) << text;

  ReplayOptions in_time = o;
  in_time.from_s = 0.1;
  EXPECT_FALSE(run_replay(in_time).report.contains("warnings"));

  const fs::path dir = own_dir("branch_from_cli");
  for (const char* from : {"50", "0.01"}) {  // past the end; before the first snapshot
    const fs::path out = dir / "out.json", err = dir / "err.txt";
    const Command cli =
        // In a subshell: run_command sends the stderr it sees to the stdout it reads.
        run_command("(" + shell_quote(serosa_exe().string()) + " replay " +
                    shell_quote(recording().string()) + " --headless --from " + from + " > " +
                    shell_quote(out.string()) + " 2> " + shell_quote(err.string()) + ")");
    ASSERT_EQ(cli.code, 0) << file_text(err);
    nlohmann::json report;
    EXPECT_NO_THROW(report = nlohmann::json::parse(file_text(out))) << file_text(out);
    EXPECT_EQ(report["recording"]["steps"], kSteps);
    const bool past = std::string(from) == "50";
    EXPECT_EQ(file_text(err).find("warning: --from 50 s is past the end") != std::string::npos,
              past)
        << file_text(err);
    if (!past) {
      EXPECT_NE(file_text(err).find("no snapshot"), std::string::npos) << file_text(err);
    }
  }
}

// ---- the mouse's takeover (no simulation: the scene and the script's poses) ----

struct Posed {
  Scene scene;
  std::vector<ToolState> tools;  // the script's inputs at the branch
};

Posed posed(const std::string& scene, const std::string& path, double t_s) {
  Posed p{load_scene(source(scene)), {}};
  const ToolPath script = read_tool_path(source(path));
  for (const Tool& t : p.scene.tools) p.tools.push_back(sample(script, t.name, t_s));
  return p;
}

// Plays `in` for `polls` steps, each output landing in `tools` as the controller's would.
void play(MouseTakeover& m, const haptics::PointerInput& in, std::vector<ToolState>& tools,
          double& t_s, std::uint64_t& step, int polls, std::set<std::size_t>* driven = nullptr) {
  for (int k = 0; k < polls; ++k) {
    for (const TakeoverInput& d : m.poll(in, t_s, step, tools)) {
      tools[d.tool] = d.input;
      if (driven != nullptr) driven->insert(d.tool);
    }
    t_s += kDt;
    ++step;
  }
}

// At 3 s of the procedure the left hand holds the grasper, the right the clip applier (jaws 0.7
// open); the others wait in their ports. Taking over moves nothing: the hands' inputs and the
// endoscope's are the recorded ones.
TEST(MouseTakeover, TheHandsTakeWhatTheRecordingsHandsHeldAndMoveNothing) {
  const Posed p = posed("config/appendectomy.toml", "config/paths/appendectomy_procedure.csv", 3.0);
  MouseTakeover m(p.scene, p.tools);
  const std::size_t grasper = tool_of(p.scene, ToolKind::kGrasper);
  const std::size_t clip = tool_of(p.scene, ToolKind::kClipApplier);
  const std::size_t scope = tool_of(p.scene, ToolKind::kEndoscope);
  EXPECT_EQ(m.handle_tools()[0], grasper);
  EXPECT_EQ(m.handle_tools()[1], clip);
  EXPECT_EQ(m.scope_tool(), scope);
  std::vector<ToolState> tools = p.tools;
  double t = 3.0;
  std::uint64_t step = 600;
  play(m, m.initial_input(), tools, t, step, 20);
  for (std::size_t i : {grasper, clip, scope}) {
    EXPECT_LT((tip_of(tools[i]) - tip_of(p.tools[i])).norm(), 1e-9) << i;
    EXPECT_NEAR(tools[i].jaw_rad, p.tools[i].jaw_rad, 1e-9) << i;
    EXPECT_EQ(tools[i].buttons, p.tools[i].buttons) << i;
  }
  EXPECT_NEAR(tools[clip].jaw_rad, 0.7, 1e-9);
  // The jaws move once the input asks.
  haptics::PointerInput in = m.initial_input();
  in.jaw_fraction[1] = 0.0;
  play(m, in, tools, t, step, 20);
  EXPECT_LT(tools[clip].jaw_rad, 0.5);
  // The scope moves when its control does.
  m.scope()->move(0.1, 0.0, 0.0, 0.0);
  play(m, in, tools, t, step, 1);
  EXPECT_GT((tip_of(tools[scope]) - tip_of(p.tools[scope])).norm(), 1e-4);
}

// X (as the session's key) takes every instrument of the scene in turn, on either hand, but the
// one the other hand holds; each is moved by a drag.
// The tools no hand holds keep their recorded input, or where the mouse let go of them (pedal
// up, held by no hand). Both shipped procedures: grasper, scissors, clip applier, hook and
// endoloop; stapler.
TEST(MouseTakeover, EveryInstrumentCanBeTakenAndMoved) {
  for (const auto& [scene, path] :
       {std::pair<std::string, std::string>{"config/appendectomy.toml",
                                            "config/paths/appendectomy_procedure.csv"},
        {"config/appendectomy_stapler.toml", "config/paths/appendectomy_stapler.csv"}}) {
    SCOPED_TRACE(scene);
    const Posed p = posed(scene, path, 3.0);
    MouseTakeover m(p.scene, p.tools);
    std::vector<ToolState> tools = p.tools;
    double t = 3.0;
    std::uint64_t step = 600;
    haptics::PointerInput in = m.initial_input();
    std::set<std::size_t> moved;
    std::vector<ToolState> let_go(tools.size());
    const auto take_next_and_drag = [&](std::size_t h) {
      const std::optional<std::size_t> before = m.handle_tools()[h];
      const std::vector<ToolState> was = tools;
      ++in.exchanges[h];
      std::set<std::size_t> driven;
      play(m, in, tools, t, step, 1, &driven);
      const std::size_t now = *m.handle_tools()[h];
      EXPECT_NE(before, now);
      if (before) {
        EXPECT_FALSE(pedal_down(tools[*before]));
        EXPECT_FALSE(holder(tools[*before]).has_value());
        let_go[*before] = tools[*before];
      }
      EXPECT_FALSE(in_port(tools[now])) << p.scene.tools[now].name;
      EXPECT_EQ(holder(tools[now]), h == 0 ? Hand::kLeft : Hand::kRight);
      if (in_port(was[now]) && p.scene.tools[now].trocar_m) {  // in through its port, just inside
        EXPECT_NEAR((tip_of(tools[now]) - *p.scene.tools[now].trocar_m).norm(), 0.01, 1e-6)
            << p.scene.tools[now].name;
      }
      const Vec3 taken = tip_of(tools[now]);
      // A 40-pixel drag across the shaft (along it, an instrument just inside its port would
      // only be drawn back against its shortest insertion).
      const auto& q = tools[now].quat_wxyz;
      const Vec3 shaft = Quat(q[0], q[1], q[2], q[3]).normalized() * Vec3::UnitZ();
      Vec3 across = shaft.cross(Vec3::UnitZ());
      if (across.norm() < 0.1) across = shaft.cross(Vec3::UnitX());
      across.normalize();
      for (std::size_t k = 0; k < 3; ++k)
        in.move_m[h][k] += 0.004 * across[static_cast<Eigen::Index>(k)];
      play(m, in, tools, t, step, 30, &driven);
      EXPECT_GT((tip_of(tools[now]) - taken).norm(), 0.002) << p.scene.tools[now].name;
      moved.insert(now);
      // Nothing else moved: only the hands' instruments, the scope and the one let go of.
      for (std::size_t i : driven) {
        const bool hand = m.handle_tools()[0] == i || m.handle_tools()[1] == i;
        EXPECT_TRUE(hand || i == m.scope_tool() || i == before) << p.scene.tools[i].name;
      }
      for (std::size_t i = 0; i < tools.size(); ++i) {
        const bool hand = m.handle_tools()[0] == i || m.handle_tools()[1] == i;
        const std::vector<std::size_t> left = m.left_tools();
        if (hand || i == m.scope_tool()) continue;
        if (std::find(left.begin(), left.end(), i) != left.end()) {
          EXPECT_TRUE(same(tools[i], let_go[i])) << p.scene.tools[i].name;
        } else {
          EXPECT_TRUE(same(tools[i], p.tools[i])) << p.scene.tools[i].name;
        }
      }
    };
    std::size_t instruments = 0;
    for (const Tool& tool : p.scene.tools) instruments += tool.kind != ToolKind::kEndoscope;
    // Each hand's X goes round every instrument the other hand does not hold.
    for (std::size_t h = 0; h < 2; ++h)
      for (std::size_t k = 0; k + 1 < instruments; ++k) take_next_and_drag(h);
    std::set<ToolKind> kinds;
    for (std::size_t i : moved) kinds.insert(p.scene.tools[i].kind);
    EXPECT_EQ(moved.size(), instruments);
    EXPECT_FALSE(kinds.contains(ToolKind::kEndoscope));
    EXPECT_EQ(kinds.size(), instruments);
  }
}

// The hook's pedal follows P from the recorded state and goes up when the hand lets go of it;
// take() refuses the endoscope and the other hand's instrument.
TEST(MouseTakeover, PedalAndDirectChoice) {
  const Posed p = posed("config/appendectomy.toml", "config/paths/appendectomy_procedure.csv", 3.0);
  MouseTakeover m(p.scene, p.tools);
  const std::size_t hook = tool_of(p.scene, ToolKind::kHook);
  const std::size_t clip = tool_of(p.scene, ToolKind::kClipApplier);
  std::vector<ToolState> tools = p.tools;
  double t = 3.0;
  std::uint64_t step = 600;
  haptics::PointerInput in = m.initial_input();
  m.take(0, hook, tools, in);
  EXPECT_EQ(m.handle_tools()[0], hook);
  play(m, in, tools, t, step, 2);
  EXPECT_FALSE(pedal_down(tools[hook]));
  EXPECT_EQ(holder(tools[hook]), Hand::kLeft);
  in.buttons[0] ^= kPedalButton;  // P
  play(m, in, tools, t, step, 2);
  EXPECT_TRUE(pedal_down(tools[hook]));
  m.take(0, tool_of(p.scene, ToolKind::kScissors), tools, in);
  play(m, in, tools, t, step, 1);
  EXPECT_FALSE(pedal_down(tools[hook]));
  EXPECT_THROW(m.take(0, clip, tools, in), std::invalid_argument);
  EXPECT_THROW(m.take(0, tool_of(p.scene, ToolKind::kEndoscope), tools, in), std::invalid_argument);
  EXPECT_THROW(m.take(2, hook, tools, in), std::out_of_range);
  EXPECT_THROW(m.take(0, 99, tools, in), std::out_of_range);
}

// ---- the branch's line ----

TEST(BranchBanner, SaysWhoDrivesWhat) {
  EXPECT_EQ(clock_time(5.2), "0:05.2");
  EXPECT_EQ(clock_time(65.25), "1:05.3");
  EXPECT_EQ(clock_time(59.97), "1:00.0");
  EXPECT_EQ(clock_time(0.0), "0:00.0");

  const Posed p = posed("config/appendectomy.toml", "config/paths/appendectomy_procedure.csv", 3.0);
  MouseTakeover m(p.scene, p.tools);
  EXPECT_EQ(branch_banner(p.scene, m, {600, kDt, 0, true}),
            "BRANCH at 0:03.0 (step 600): the mouse drives grasper (left, active), clip-applier "
            "(right) and endoscope (right button); the recording drives the rest. Tab: other "
            "hand, X: next instrument");
  std::vector<ToolState> tools = p.tools;
  haptics::PointerInput in = m.initial_input();
  ++in.exchanges[1];
  (void)m.poll(in, 3.0, 600, tools);
  EXPECT_EQ(branch_banner(p.scene, m, {1041, kDt, 1, false}),
            "BRANCH at 0:05.2 (step 1041): the mouse drives grasper (left), hook (right, active) "
            "and endoscope (right button); clip-applier stays where the mouse left it; the rest "
            "hold the recording's last pose. Tab: other hand, X: next instrument");
}

// At the procedure's start the right hand holds nothing: said, so that X is pressed there.
TEST(BranchBanner, AnEmptyHandIsSaid) {
  const Posed p = posed("config/appendectomy.toml", "config/paths/appendectomy_procedure.csv", 0.0);
  MouseTakeover m(p.scene, p.tools);
  EXPECT_FALSE(m.handle_tools()[1].has_value());
  EXPECT_EQ(branch_banner(p.scene, m, {0, kDt, 1, true}),
            "BRANCH at 0:00.0 (step 0): the mouse drives grasper (left), no instrument (right, "
            "active) and endoscope (right button); the recording drives the rest. Tab: other "
            "hand, X: next instrument");
}

// A scripted transection's takeover (no hands in the recording): the first two instruments.
TEST(BranchBanner, AScriptWithoutHandsGivesTheFirstTwoInstruments) {
  const Posed p = posed("config/transection.toml", "config/paths/appendectomy.csv", 0.5);
  MouseTakeover m(p.scene, p.tools);
  EXPECT_EQ(branch_banner(p.scene, m, {100, kDt, 0, true}),
            "BRANCH at 0:00.5 (step 100): the mouse drives grasper (left, active), scissors "
            "(right) and endoscope (right button). Tab: other hand, X: next instrument");
}

}  // namespace
}  // namespace serosa::app
