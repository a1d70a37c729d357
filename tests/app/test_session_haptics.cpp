// The haptic loop in the trainee session: mouse-driven instruments through the 1 kHz
// loop, haptic contact planes from the collision BVH, the session under Xvfb with its report and
// recording, and branching from a replay with the mouse (controller level and in the window).
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <chrono>
#include <cstdio>
#include <fstream>
#include <thread>

#include <nlohmann/json.hpp>

#include "app/assemble_state.h"
#include "app/compose.h"
#include "app/headless.h"
#include "app_test_util.h"
#include "contact/tool_contact_stage.h"
#include "engine/jaw_range.h"
#include "engine/scene/scene.h"
#include "engine/shell_command.h"
#include "engine/sim_state.h"
#include "haptics/haptic_loop.h"
#include "haptics/haptics_stage.h"
#include "haptics/trocar_kinematics.h"
#include "recording/recording_reader.h"
#include "replay/mouse_takeover.h"
#include "replay/replay.h"
#include "replay/replay_controller.h"
#include "window/pointer_control.h"

namespace serosa::app {
namespace {

using namespace serosa::replay;

using namespace serosa::app::testing;
using contact::kHapticStiffness;

// Each test writes into a folder of its own (CTest runs tests in parallel processes).
fs::path own_dir(const std::string& name) {
  const ::testing::TestInfo* t = ::testing::UnitTest::GetInstance()->current_test_info();
  std::string full = name;
  if (t != nullptr) full.append("_").append(t->name());
  return out_dir(full);
}

// The beam (0.1 x 0.01 x 0.01 m, x from 0 to 0.1, clamped at x = 0) with one grasper.
std::string beam_scene(const std::string& effects, const std::string& device,
                       const std::string& young = "1e6") {
  std::string toml = "[scene]\ndt = 0.005\neffects = [";
  toml.append(effects).append("]\n[[organ]]\nname = \"beam\"\nmesh = \"");
  toml.append(source("assets/beam_coarse.msh").string())
      .append("\"\nyoung = ")
      .append(young)
      .append("\ndensity = 1000\n")
      .append("fixed = { box = [[-0.001, -1, -1], [0.0001, 1, 1]] }\n")
      .append("[solver]\nkind = \"pcg\"\n[record]\nhash_every = 10\n")
      .append("[[tool]]\nname = \"grasper\"\nkind = \"grasper\"\ndevice = \"")
      .append(device)
      .append("\"\ntrocar = [0.05, 0.1, 0.0]\n");
  return toml;
}

Vec3 tip_of(const ToolState& t) { return Vec3(t.tip_m[0], t.tip_m[1], t.tip_m[2]); }

// Field by field (the struct has padding).
bool same(const ToolState& a, const ToolState& b) {
  return a.tick == b.tick && a.time_s == b.time_s && a.tip_m == b.tip_m &&
         a.quat_wxyz == b.quat_wxyz && a.jaw_rad == b.jaw_rad && a.buttons == b.buttons;
}

// A mouse-driven grasper under "haptics": the loop ticks (its live status counts), the solver
// consumes the loop's tool states, and they follow the pointer: 100 px of drag = 0.2 rad of yaw
// about the trocar, one scroll step = 5 mm deeper.
TEST(SessionHaptics, MouseDrivesTheToolThroughTheLoop) {
  const fs::path dir = own_dir("session_haptics");
  std::ofstream(dir / "scene.toml") << beam_scene("\"fem\", \"haptics\"", "mouse");
  const Scene scene = load_scene(dir / "scene.toml");
  AssembledScene assembled = assemble_state(scene);
  Composition comp = compose(scene, assembled);
  ASSERT_NE(comp.haptics, nullptr);
  EXPECT_EQ(comp.haptics->device_kind(), DeviceKind::kMouse);
  ASSERT_TRUE(comp.haptics->handle_tools()[0].has_value());
  EXPECT_FALSE(comp.haptics->handle_tools()[1].has_value());

  const Vec3 aim = [&] {
    Vec3 s = Vec3::Zero();
    for (const Vec3& x : assembled.state.mesh.x) s += x;
    return Vec3(s / static_cast<double>(assembled.state.mesh.x.size()));
  }();
  const MouseHandle mh = mouse_handle(scene.tools[0], 0, aim);
  EXPECT_LT((mh.trocar.pivot_m - Vec3(0.05, 0.1, 0.0)).norm(), 1e-12);

  haptics::PointerInput in;
  in.move_m[0] = {0.004, -0.002, 0.0};
  in.depth_steps[0] = 1.0;
  in.jaw_fraction[0] = 1.0;
  comp.haptics->feed_pointer(in);
  const ToolState rest = haptics::forward(mh.trocar, mh.rest);
  haptics::JointState q = haptics::reach(mh.trocar, tip_of(rest) + Vec3(0.004, -0.002, 0.0),
                                         mh.rest, haptics::MouseMapping{});
  q.insertion_m += haptics::MouseMapping{}.m_per_step;
  const ToolState expected = haptics::forward(mh.trocar, q);

  // The loop eases towards the goal (30 ms) and opens the jaws at 4 rad/s: half a second.
  SimState& state = assembled.state;
  const auto until = std::chrono::steady_clock::now() + std::chrono::milliseconds(600);
  while (std::chrono::steady_clock::now() < until) {
    comp.runner->step(state);
    std::this_thread::sleep_for(std::chrono::milliseconds(2));
  }
  comp.runner->step(state);
  const std::uint64_t ticks = comp.haptics->status().tick;
  EXPECT_GT(ticks, 100u);  // 600 ms of a 1 kHz loop, however loaded the machine
  const ToolState& t = state.tools[0];
  EXPECT_GT(t.tick, 0u);  // the loop's state, not a default
  EXPECT_LT((tip_of(t) - tip_of(expected)).norm(), 1e-6);
  EXPECT_NEAR(t.jaw_rad, max_jaw_rad(scene.tools[0].kind), 1e-12);
  const nlohmann::json tel = comp.haptics->telemetry_json();  // stops the loop
  EXPECT_EQ(tel["device"], "mouse");
  EXPECT_GE(tel["ticks"].get<std::uint64_t>(), ticks);
}

// A grasper whose tip is pressed 2 mm into the top of the beam (pointing down, 12 mm from the
// clamp, a stiff beam: the tissue stays put under the jaws' contact push): the contact stage
// finds the nearest surface point on the top face (outward normal +y), the haptics stage
// publishes that plane, and the 1 kHz loop renders a tip force along +y, opposing the
// penetration (k * depth = 500 N/m * 2 mm = 1 N).
TEST(SessionHaptics, ToolPressedIntoTheOrganFeelsAForceOpposingPenetration) {
  const fs::path dir = own_dir("haptic_contact");
  // Pointing down (+z of the tool = -y of the scene), tip 2 mm below the top face (y = 5 mm).
  std::ofstream(dir / "path.csv")
      << "t,tool,px,py,pz,qw,qx,qy,qz,jaw\n"
         "0,grasper,0.012,0.003,0.001,0.7071067811865476,0.7071067811865476,0,0,0\n"
         "10,grasper,0.012,0.003,0.001,0.7071067811865476,0.7071067811865476,0,0,0\n";
  std::ofstream(dir / "scene.toml")
      << beam_scene("\"fem\", \"surface\", \"contact\", \"haptics\"", "script:path.csv", "1e8");
  const Scene scene = load_scene(dir / "scene.toml");
  AssembledScene assembled = assemble_state(scene);
  Composition comp = compose(scene, assembled);
  ASSERT_NE(comp.haptics, nullptr);
  ASSERT_NE(comp.contact, nullptr);
  SimState& state = assembled.state;
  for (int i = 0; i < 30; ++i) {
    comp.runner->step(state);
    std::this_thread::sleep_for(std::chrono::milliseconds(3));
  }
  // The plane the contact stage found for the tip.
  ASSERT_EQ(state.events.contact_planes.size(), scene.tools.size());
  const std::optional<haptics::ContactPlane> plane = state.events.contact_planes[0];
  ASSERT_TRUE(plane.has_value());
  const Vec3 n(plane->normal[0], plane->normal[1], plane->normal[2]);
  EXPECT_GT(n.y(), 0.99);
  EXPECT_NEAR(plane->point_m[1], 0.005, 5e-4);
  const Vec3 tip = tip_of(state.tools[0]);
  const double depth = (Vec3(plane->point_m[0], plane->point_m[1], plane->point_m[2]) - tip).dot(n);
  EXPECT_NEAR(depth, 0.002, 5e-4);
  const haptics::ContactModel model = comp.haptics->last_model();
  EXPECT_EQ(model.tools[0].n_contacts, 1u);
  // The loop renders it: sampled over 30 more steps, its tip force pushes the tip out (never in)
  // and reaches k * depth. (A loaded machine may stall the loop past its watchdog now and then:
  // such a tick renders zero and the force ramps back, so the largest sample is checked.)
  double most = 0.0;
  double least = 0.0;
  Vec3 f_most = Vec3::Zero();
  for (int i = 0; i < 30; ++i) {
    comp.runner->step(state);
    std::this_thread::sleep_for(std::chrono::milliseconds(3));
    const haptics::LoopStatus st = comp.haptics->status();
    const Vec3 f(st.tip_force_N[0][0], st.tip_force_N[0][1], st.tip_force_N[0][2]);
    least = std::min(least, f.dot(n));
    if (f.dot(n) > most) {
      most = f.dot(n);
      f_most = f;
    }
  }
  EXPECT_GT(most, 0.5) << f_most.transpose();
  EXPECT_NEAR(f_most.norm(), kHapticStiffness * depth, 0.2) << f_most.transpose();
  EXPECT_GE(least, -1e-9);
  comp.haptics->stop();

  // A tool away from every surface gets no plane, hence no contact force.
  ToolState far = state.tools[0];
  far.tip_m = {0.05, 0.05, 0.0};
  state.tools[0] = far;
  comp.contact->step(StepContext{state.step, state.time_s, scene.settings.dt_s}, state);
  EXPECT_FALSE(state.events.contact_planes[0].has_value());
}

// Records a scripted grasper run on the beam (fem, surface, contact): 60 steps, hashes every 10.
fs::path record_beam(const fs::path& dir) {
  std::ofstream(dir / "path.csv")
      << "t,tool,px,py,pz,qw,qx,qy,qz,jaw\n"
         "0,grasper,0.05,0.03,0,0.7071067811865476,0.7071067811865476,0,0,0.5\n"
         "0.3,grasper,0.07,0.02,0,0.7071067811865476,0.7071067811865476,0,0,0.5\n";
  std::ofstream(dir / "scene.toml")
      << beam_scene("\"fem\", \"surface\", \"contact\"", "script:path.csv");
  HeadlessOptions o;
  o.scene = dir / "scene.toml";
  o.steps = 60;
  o.record = dir / "run.lapr";
  o.progress = false;
  (void)run_headless(o);
  return *o.record;
}

// Branch from replay with the mouse: pause at step 25, take over, and play a scripted sequence of
// pointer inputs (drag, insert, close the jaws) standing in for the user. Taking over moves
// nothing by itself; the tool then follows the device; the branch file replays --verify bit for
// bit and its first 25 steps (inputs and hashes) are the original's.
TEST(SessionHaptics, MouseTakeoverBranchReplaysVerifiedWithTheOriginalPrefix) {
  const fs::path dir = own_dir("mouse_branch");
  const fs::path rec = record_beam(dir);
  ReplayControllerOptions co;
  co.snapshot_every_s = 0.05;  // as in the window: seeks restore snapshots
  ReplayController c(rec, co);
  c.seek_step(40);
  c.seek_step(25);  // backwards, from a snapshot: still the recorded state
  ASSERT_TRUE(c.exact());
  EXPECT_EQ(c.steps_taken(), 25u);
  c.set_paused(true);
  const ToolState before = c.state().tools[0];
  const fs::path file = dir / "branch.lapr";
  c.branch(file);
  MouseTakeover take(c.scene(), c.state().tools);
  ASSERT_TRUE(take.handle_tools()[0].has_value());
  haptics::PointerInput in = take.initial_input();
  const double held = in.jaw_fraction[0];
  EXPECT_NEAR(held * max_jaw_rad(c.scene().tools[0].kind), 0.5, 1e-12);  // as recorded
  take.apply(in, c);
  ASSERT_TRUE(c.step_forward());
  EXPECT_LT((tip_of(c.state().tools[0]) - tip_of(before)).norm(), 1e-12);  // no jump
  EXPECT_NEAR(c.state().tools[0].jaw_rad, 0.5, 1e-12);
  for (int i = 0; i < 34; ++i) {
    in.move_m[0][0] += 4.0 * window::kDragMetresPerPixel;  // drag 4 px right a step
    if (i % 10 == 0) in.depth_steps[0] -= 1.0;             // retract
    in.jaw_fraction[0] = i < 20 ? held : 0.0;              // held open (as recorded), then closing
    take.apply(in, c);
    ASSERT_TRUE(c.step_forward());
  }
  EXPECT_EQ(c.steps_taken(), 60u);
  const ToolState after = c.state().tools[0];
  EXPECT_GT((tip_of(after) - tip_of(before)).norm(), 0.01);  // 136 px = 14 mm, 12 mm back
  EXPECT_LT(after.jaw_rad, 0.5);
  const std::uint64_t branch_hash = state_hash(c.state());
  c.end_branch();

  const recording::Recording parent = recording::read_recording(rec);
  const recording::Recording b = recording::read_recording(file);
  ASSERT_EQ(b.inputs.size(), 60u);
  for (std::size_t s = 0; s < 25; ++s) {
    ASSERT_EQ(b.inputs[s].size(), parent.inputs[s].size());
    for (std::size_t k = 0; k < b.inputs[s].size(); ++k)
      EXPECT_TRUE(same(b.inputs[s][k], parent.inputs[s][k])) << s;
  }
  for (const auto& [step, hash] : parent.hashes)
    if (step < 25) {
      EXPECT_EQ(b.hashes.at(step), hash) << step;
    }
  EXPECT_NE(b.hashes.at(59), parent.hashes.at(59));  // the branch went its own way

  ReplayOptions o;
  o.recording = file;
  o.verify = true;
  o.progress = false;
  const ReplayResult r = run_replay(o);
  EXPECT_EQ(r.steps, 60u);
  EXPECT_EQ(r.hashes_checked, 6u);
  EXPECT_FALSE(r.diverged_at.has_value());
  EXPECT_EQ(r.report["state_hash"], hash_hex(branch_hash));
  // And with the command line.
  const CliResult cli = run_serosa("replay '" + file.string() + "' --headless --verify");
  EXPECT_EQ(cli.code, 0) << cli.out;
}

// The trainee session under Xvfb with a mouse-driven grasper and "haptics": the loop runs beside
// the solver and render threads, the report carries its telemetry, the recording of what the
// solver consumed replays --verify; then the replay window branches at 0.2 s (--branch-at) and
// its branch file verifies too.
TEST(SessionHaptics, SessionUnderXvfbRecordsAndReportsTheLoop) {
  const fs::path dir = own_dir("session_xvfb");
  std::ofstream(dir / "scene.toml")
      << beam_scene("\"fem\", \"surface\", \"contact\", \"render\", \"haptics\"", "mouse");
  const std::string xvfb =
      "xvfb-run -a -s '-screen 0 1280x720x24' '" + serosa_exe().string() + "' ";
  const Command run =
      run_command(xvfb + "run '" + (dir / "scene.toml").string() + "' --seconds 2 " + "--record '" +
                  (dir / "s.lapr").string() + "' --report '" + (dir / "s.json").string() + "'");
  ASSERT_EQ(run.code, 0) << run.output;
  nlohmann::json rep;
  std::ifstream(dir / "s.json") >> rep;
  ASSERT_TRUE(rep.contains("haptics")) << rep.dump(1);
  EXPECT_EQ(rep["haptics"]["device"], "mouse");
  EXPECT_GT(rep["haptics"]["ticks"].get<std::uint64_t>(), 100u) << rep["haptics"].dump(1);
  const std::int64_t steps = rep["steps_taken"].get<std::int64_t>();
  EXPECT_GT(steps, 10);
  // The solver's pace as the trainee saw it, and its step times.
  const double factor = rep["real_time_factor"].get<double>();
  EXPECT_GT(factor, 0.0);
  EXPECT_LE(factor, 1.0 + 1e-9);  // paced to the clock
  EXPECT_NEAR(factor, rep["simulated_time_s"].get<double>() / rep["wall_time_s"].get<double>(),
              1e-9);
  EXPECT_GT(rep["step_time_ms"]["p50"].get<double>(), 0.0);
  EXPECT_LE(rep["step_time_ms"]["p99"].get<double>(), rep["step_time_ms"]["max"].get<double>());
  EXPECT_EQ(rep["recording"]["steps"].get<std::int64_t>(), steps);
  const recording::Recording rec = recording::read_recording(dir / "s.lapr");
  EXPECT_TRUE(rec.complete);
  ASSERT_EQ(static_cast<std::int64_t>(rec.inputs.size()), steps);
  EXPECT_GT(rec.inputs.back()[0].tick, 0u);  // the loop's states were consumed and recorded
  const CliResult verify =
      run_serosa("replay '" + (dir / "s.lapr").string() + "' --headless --verify");
  EXPECT_EQ(verify.code, 0) << verify.out;

  const Command branch =
      run_command(xvfb + "replay '" + (dir / "s.lapr").string() +
                  "' --seconds 1.5 --branch-at 0.05 --branch '" + (dir / "b.lapr").string() + "'");
  ASSERT_EQ(branch.code, 0) << branch.output;
  EXPECT_NE(branch.output.find("branched at"), std::string::npos) << branch.output;
  const recording::Recording b = recording::read_recording(dir / "b.lapr");
  EXPECT_TRUE(b.complete);
  ASSERT_FALSE(b.events.empty());
  const std::uint64_t at = b.events[0].first;
  EXPECT_GE(at, 10u);  // 0.05 s at dt 5 ms
  ASSERT_GE(b.inputs.size(), at);
  for (std::size_t s = 0; s < at; ++s) EXPECT_TRUE(same(b.inputs[s][0], rec.inputs[s][0])) << s;
  const CliResult bverify =
      run_serosa("replay '" + (dir / "b.lapr").string() + "' --headless --verify");
  EXPECT_EQ(bverify.code, 0) << bverify.out;
}

// One scene, every use: the default scene, whose instruments are scripted, is the trainee's in
// the window. With no rig plugged in the grasper and scissors follow the mouse through the
// haptic loop, and the session's recording replays --verify from the scene as written (whose
// effects do not list the loop); with --path the tool path plays and no loop runs.
TEST(SessionHaptics, TheDefaultSceneInAWindowIsDrivenByTheTrainee) {
  const fs::path dir = own_dir("default_scene_window");
  const std::string xvfb =
      "xvfb-run -a -s '-screen 0 1280x720x24' '" + serosa_exe().string() + "' ";
  std::string scene = "'";  // (one append at a time: GCC 12 warns on "'" + string + "'")
  scene.append(source("config/transection.toml").string()).append("'");
  const Command run =
      run_command(xvfb + "run " + scene + " --seconds 2 --record '" + (dir / "s.lapr").string() +
                  "' --report '" + (dir / "s.json").string() + "'");
  ASSERT_EQ(run.code, 0) << run.output;
  EXPECT_NE(run.output.find("the instruments follow the mouse"), std::string::npos) << run.output;
  nlohmann::json rep;
  std::ifstream(dir / "s.json") >> rep;
  ASSERT_TRUE(rep.contains("haptics")) << rep.dump(1);
  EXPECT_EQ(rep["haptics"]["device"], "mouse");
  EXPECT_TRUE(rep["haptics"]["device_connected"].get<bool>());
  EXPECT_GT(rep["haptics"]["ticks"].get<std::uint64_t>(), 100u) << rep["haptics"].dump(1);
  const CliResult verify =
      run_serosa("replay '" + (dir / "s.lapr").string() + "' --headless --verify");
  EXPECT_EQ(verify.code, 0) << verify.out;

  // 5 s: a sanitizer build under load takes its first steps only after a second or more.
  const Command scripted = run_command(xvfb + "run " + scene + " --seconds 5 --path '" +
                                       source("config/paths/appendix_transection.csv").string() +
                                       "' --report '" + (dir / "p.json").string() + "'");
  ASSERT_EQ(scripted.code, 0) << scripted.output;
  nlohmann::json prep;
  std::ifstream(dir / "p.json") >> prep;
  EXPECT_FALSE(prep.contains("haptics")) << prep.dump(1);
  EXPECT_GT(prep["steps_taken"].get<std::int64_t>(), 10);
}

// The trainee drives with the mouse: a drag across the window (xdotool, under Xvfb) moves the
// active instrument (the grasper), so its path in the session report grows well beyond that of
// an equally long session without input (as many frames), in which no instrument moves at all;
// the I key pushes the endoscope in.
TEST(SessionHaptics, DraggingTheMouseInTheWindowMovesTheInstrument) {
  const fs::path dir = own_dir("drag_window");
  const auto session = [&](bool drag) {
    const fs::path report = dir / (drag ? "drag.json" : "still.json");
    std::string cmd = "xvfb-run -a -s '-screen 0 1280x720x24' '";
    cmd.append(source("tests/app/drag_in_window.sh").string()).append("' '");
    cmd.append(serosa_exe().string()).append("' '");
    cmd.append(source("config/transection.toml").string()).append("' '");
    cmd.append(report.string()).append(drag ? "' 1" : "' 0");
    const Command run = run_command(cmd);
    EXPECT_EQ(run.code, 0) << run.output;
    nlohmann::json rep;
    std::ifstream(report) >> rep;
    return rep;
  };
  const nlohmann::json still = session(false);
  const nlohmann::json dragged = session(true);
  ASSERT_TRUE(still.contains("metrics")) << still.dump(1);
  ASSERT_TRUE(dragged.contains("metrics")) << dragged.dump(1);
  for (const auto& [tool, length] : still["metrics"]["path_length_m"].items())
    EXPECT_EQ(length.get<double>(), 0.0) << tool << " moved without input";
  EXPECT_GT(dragged["metrics"]["path_length_m"]["grasper"].get<double>(),
            still["metrics"]["path_length_m"]["grasper"].get<double>() + 0.02)
      << dragged["metrics"].dump(1);
  EXPECT_EQ(dragged["metrics"]["path_length_m"]["scissors"].get<double>(), 0.0);
  // The endoscope is the trainee's too: two presses of I pushed it 1 cm in.
  const double scope = dragged["metrics"]["path_length_m"]["endoscope"].get<double>();
  EXPECT_NEAR(scope, 0.01, 1e-9) << dragged["metrics"].dump(1);
}

// The whole appendectomy by hand needs every instrument: pressing X three times (xdotool, under
// Xvfb), each followed by a drag, brings in three instruments in turn through their ports and
// moves each; the report lists the exchanges, and the recording replays them bit for bit.
TEST(SessionHaptics, PressingXBringsInTheNextInstrument) {
  const fs::path dir = own_dir("exchange_window");
  const fs::path report = dir / "x.json", recording = dir / "x.lapr";
  std::string cmd = "xvfb-run -a -s '-screen 0 1280x720x24' '";
  cmd.append(source("tests/app/exchange_in_window.sh").string()).append("' '");
  cmd.append(serosa_exe().string()).append("' '");
  cmd.append(source("config/appendectomy.toml").string()).append("' '");
  cmd.append(report.string()).append("' '").append(recording.string()).append("'");
  const Command run = run_command(cmd);
  ASSERT_EQ(run.code, 0) << run.output;
  nlohmann::json rep;
  std::ifstream(report) >> rep;
  const nlohmann::json& m = rep["metrics"];
  ASSERT_TRUE(m.contains("exchanges")) << m.dump(1);
  EXPECT_GE(m["exchanges"].size(), 2u) << m["exchanges"].dump(1);
  for (const auto& e : m["exchanges"]) {
    EXPECT_EQ(e["hand"], "left");  // the active hand, as the session starts
    EXPECT_NE(e["from"], e["to"]);
  }
  int moved = 0;
  for (const auto& [tool, length] : m["path_length_m"].items())
    if (tool != "endoscope" && length.get<double>() > 0.005) ++moved;
  EXPECT_GE(moved, 3) << m["path_length_m"].dump(1);
  const CliResult verify = run_serosa("replay '" + recording.string() + "' --headless --verify");
  EXPECT_EQ(verify.code, 0) << verify.out;
  // Restored from a snapshot half way through the session, after its first exchanges, the
  // replay goes on as the session did: every later hash equal. (Under a sanitizer the session
  // may not reach its first snapshot, a second in: it then replays from step 0.)
  const auto steps = rep["recording"]["steps"].get<double>();
  const fs::path late = dir / "late.json";
  const CliResult from =
      run_serosa("replay '" + recording.string() + "' --headless --verify --from " +
                 std::to_string(0.5 * steps * 0.005) + " --report '" + late.string() + "'");
  EXPECT_EQ(from.code, 0) << from.out;
  nlohmann::json lr;
  std::ifstream(late) >> lr;
  if (rep["recording"]["snapshots"].get<int>() > 1) {
    EXPECT_GT(lr["start_step"].get<std::uint64_t>(), 0u) << lr.dump(1);
  }
  EXPECT_GT(lr["verify"]["hashes_checked"].get<std::uint64_t>(), 0u) << lr["verify"].dump(1);
  EXPECT_TRUE(lr["verify"]["ok"].get<bool>()) << lr["verify"].dump(1);
}

}  // namespace
}  // namespace serosa::app
