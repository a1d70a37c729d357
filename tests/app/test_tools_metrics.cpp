// Tools acting on tissue and the metrics they are scored by: stress and elastic forces against
// closed forms, a grasper that grabs, lifts and lets go, a shaft pressing on a beam, two tools at
// once, and metrics of a scripted run.
#include <gtest/gtest.h>

#include <algorithm>

#include <cmath>
#include <fstream>
#include <random>

#include "app/assemble_state.h"
#include "app/compose.h"
#include "app_test_util.h"
#include "contact/tool_contact_stage.h"
#include "engine/instrument_hold.h"
#include "engine/scene/scene.h"
#include "engine/sim_state.h"
#include "engine/tissue_stress.h"
#include "engine/tool_geometry.h"
#include "fem/fem_stage.h"
#include "metrics/metrics_stage.h"
#include "support/block_copy.h"
#include "support/test_meshes.h"

namespace serosa::app {
namespace {

using namespace serosa::app::testing;

TetMesh one_tet() {
  TetMesh m;
  m.add_node(Vec3(0, 0, 0));
  m.add_node(Vec3(1, 0, 0));
  m.add_node(Vec3(0, 1, 0));
  m.add_node(Vec3(0, 0, 1));
  m.add_tet({0, 1, 2, 3}, 1);
  m.fill_node_state();
  return m;
}

TEST(TissueStress, RigidMotionIsStressFreeAndStretchMatchesClosedForm) {
  Material mat;
  mat.young_pa = 1e4;
  mat.poisson = 0.3;
  const Lame l = lame(mat);
  TetMesh m = one_tet();
  const Mat3 r = Eigen::AngleAxisd(0.7, Vec3(1, 2, 3).normalized()).toRotationMatrix();
  for (std::size_t i = 0; i < 4; ++i) m.x[i] = r * m.rest[i] + Vec3(0.1, -2, 3);
  EXPECT_LT(von_mises_pa(m, 0, l), 1e-9 * mat.young_pa);
  LameTable table;
  table.fallback = l;
  std::vector<std::uint8_t> all(4, 1);
  std::vector<Vec3> f(4, Vec3::Zero());
  add_elastic_forces(m, table, all, f);
  for (const Vec3& fi : f) EXPECT_LT(fi.norm(), 1e-9 * mat.young_pa);
  // Uniaxial stretch F = diag(1 + e, 1, 1): von Mises of S = |S11 - S22| = 2 mu E11.
  const double e = 0.02;
  for (std::size_t i = 0; i < 4; ++i)
    m.x[i] = Vec3((1 + e) * m.rest[i].x(), m.rest[i].y(), m.rest[i].z());
  const double e11 = 0.5 * ((1 + e) * (1 + e) - 1);
  EXPECT_NEAR(von_mises_pa(m, 0, l), 2 * l.mu * e11, 1e-9 * mat.young_pa);
  // Forces sum to zero (no net force from internal stress) and pull the stretched node back.
  std::fill(f.begin(), f.end(), Vec3::Zero());
  add_elastic_forces(m, table, all, f);
  Vec3 sum = Vec3::Zero();
  for (const Vec3& fi : f) sum += fi;
  EXPECT_LT(sum.norm(), 1e-9 * mat.young_pa);
  EXPECT_LT(f[1].x(), 0.0);
}

LameTable two_materials() {
  Material soft, stiff;
  soft.young_pa = 3e3;
  soft.poisson = 0.45;
  stiff.young_pa = 8e4;
  stiff.poisson = 0.3;
  LameTable table;
  table.groups[1] = lame(soft);
  table.groups[2] = lame(stiff);
  return table;
}

// Moves every node by up to `amount` (m) in each coordinate from its rest position.
void deform(TetMesh& m, std::mt19937& rng, double amount) {
  std::uniform_real_distribution<double> u(-amount, amount);
  for (std::size_t i = 0; i < m.x.size(); ++i) m.x[i] = m.rest[i] + Vec3(u(rng), u(rng), u(rng));
}

double peak_per_tet(const TetMesh& m, const LameTable& table) {
  double peak = 0.0;
  for (std::int32_t t = 0; t < m.num_tets(); ++t)
    peak = std::max(peak, von_mises_pa(m, t, table.of(m.group[static_cast<std::size_t>(t)])));
  return peak;
}

TEST(TissueStress, PeakFromKeptRestDataIsThePerTetPeakBitForBit) {
  const LameTable table = two_materials();
  std::mt19937 rng(7);
  RestStress rest;
  for (int trial = 0; trial < 200; ++trial) {
    TetMesh m = test_meshes::kuhn_cube(3, 0.01, trial % 2 ? 0.3 : 0.0, 1 + trial);
    if (trial % 10 == 3) m.rest[5] = m.rest[0];    // a degenerate rest tet or more: stress 0
    deform(m, rng, trial % 3 == 0 ? 1e-2 : 1e-4);  // up to inverted tets
    if (trial % 10 == 7) m.x[2] = Vec3::Constant(std::nan(""));  // non-finite: those tets give 0
    fill_rest_stress(m, table, rest);
    ASSERT_EQ(peak_von_mises_pa(m, rest), peak_per_tet(m, table)) << "trial " << trial;
  }
}

TEST(Metrics, PeakStressFollowsATopologyChangeAndARestore) {
  const LameTable table = two_materials();
  Scene scene;
  SimState state;
  state.mesh = test_meshes::kuhn_cube(3, 0.01, 0.2, 3);
  std::mt19937 rng(2);
  deform(state.mesh, rng, 1e-4);
  MetricsStage metrics(scene, table);
  metrics.step({0, 0.0, 0.005}, state);
  const double before = metrics.peak_stress_pa();
  EXPECT_EQ(before, peak_per_tet(state.mesh, table));
  // Split tet 0 at its centroid and pull the new node far out: the new tets hold the peak.
  TopologyDelta split;
  split.removed_tets = {0};
  const Tet t0 = state.mesh.tets[0];
  NodeParent centroid;
  centroid.nodes = t0;
  centroid.weights = {0.25, 0.25, 0.25, 0.25};
  centroid.count = 4;
  split.added_nodes = {centroid};
  const std::int32_t c = static_cast<std::int32_t>(state.mesh.x.size());
  for (int k = 0; k < 4; ++k) {
    Tet t = t0;
    t[static_cast<std::size_t>(k)] = c;
    split.added_tets.push_back(t);
    split.added_groups.push_back(state.mesh.group[0]);
  }
  apply(state.mesh, split);
  state.mesh.x[static_cast<std::size_t>(c)] += Vec3(3e-3, 0.0, 0.0);
  metrics.step({1, 0.005, 0.005}, state);
  const double after = peak_per_tet(state.mesh, table);
  ASSERT_GT(after, before);
  EXPECT_EQ(metrics.peak_stress_pa(), after);
  // A restored stage refills its rest data: the mesh it steps next may be another of the same
  // topology version (a branch that cut elsewhere), here other rest positions, same tets.
  SimState first;
  first.mesh = test_meshes::kuhn_cube(3, 0.01, 0.2, 3);
  SimState other;
  other.mesh = test_meshes::kuhn_cube(3, 0.01, 0.2, 4);
  deform(other.mesh, rng, 1e-3);
  MetricsStage restored(scene, table);
  restored.step({0, 0.0, 0.005}, first);
  other.blocks.metrics = {};  // a snapshot taken before the first step
  restored.adopt(other);
  restored.step({1, 0.005, 0.005}, other);
  EXPECT_EQ(restored.peak_stress_pa(), peak_per_tet(other.mesh, table));
}

TEST(Metrics, DistanceToPolylineMatchesDenseSampling) {
  std::mt19937 rng(1);
  std::uniform_real_distribution<double> u(-1, 1);
  for (int trial = 0; trial < 50; ++trial) {
    std::vector<Vec3> line;
    for (int k = 0; k < 4; ++k) line.emplace_back(u(rng), u(rng), u(rng));
    const Vec3 p(u(rng), u(rng), u(rng));
    double best = 1e9;
    for (std::size_t i = 0; i + 1 < line.size(); ++i)
      for (int s = 0; s <= 2000; ++s)
        best = std::min(best, (p - (line[i] + (s / 2000.0) * (line[i + 1] - line[i]))).norm());
    const double d = distance_to_polyline(p, line);
    EXPECT_LE(d, best + 1e-12);
    EXPECT_GE(d, best - 2e-3);
  }
}

TEST(ToolGeometry, JawsOpenSymmetricallyAboutTheShaft) {
  ToolState t;
  t.tip_m = {0.01, 0.02, 0.03};
  const Eigen::Quaterniond q(Eigen::AngleAxisd(0.4, Vec3(0.3, 1, 0).normalized()));
  t.quat_wxyz = {q.w(), q.x(), q.y(), q.z()};
  const ToolFrame f = tool_frame(t);
  EXPECT_NEAR((f.tip - f.hinge).norm(), kJawLength, 1e-15);
  EXPECT_NEAR(f.forward.dot(f.side), 0.0, 1e-15);
  EXPECT_NEAR(f.side.cross(f.pin).dot(f.forward), 1.0, 1e-12);
  // Closed jaws end at the tip; open ones at +-jaw/2 from the shaft, in the jaw plane.
  EXPECT_NEAR((jaw_tip(f, 0.0, 0) - f.tip).norm(), 0.0, 1e-15);
  const Vec3 a = jaw_tip(f, 0.8, 0) - f.hinge, b = jaw_tip(f, 0.8, 1) - f.hinge;
  EXPECT_NEAR(std::acos(a.dot(b) / (a.norm() * b.norm())), 0.8, 1e-12);
  EXPECT_NEAR(a.dot(f.pin), 0.0, 1e-15);
}

// A beam scene (10 cm along +x, fixed at x = 0) with the given tools and a script.
struct BeamRun {
  Scene scene;
  AssembledScene assembled;
  Composition comp;
};
std::unique_ptr<BeamRun> beam_with_tools(const fs::path& dir, const std::string& effects,
                                         const std::string& tools, const std::string& csv,
                                         const std::string& organ_keys = "") {
  std::ofstream(dir / "path.csv") << "t,tool,px,py,pz,qw,qx,qy,qz,jaw\n" << csv;
  std::string toml =
      "[scene]\ndt = 0.005\neffects = [" + effects + "]\n[[organ]]\nname = \"beam\"\n";
  toml.append("mesh = \"").append(source("assets/beam_coarse.msh").string()).append("\"\n");
  toml.append("young = 2e4\npoisson = 0.3\ndensity = 1000\n").append(organ_keys);
  toml.append(
      "fixed = { box = [[-0.001, -1, -1], [0.0001, 1, 1]] }\n[solver]\nkind = \"cholmod\"\n");
  toml.append(tools);
  const fs::path p = dir / "scene.toml";
  std::ofstream(p) << toml;
  auto run = std::make_unique<BeamRun>();
  run->scene = load_scene(p);
  run->assembled = assemble_state(run->scene);
  run->comp = compose(run->scene, run->assembled);
  return run;
}

std::int32_t tip_node(const TetMesh& m) {
  std::int32_t tip = 0;
  for (std::int32_t i = 0; i < m.num_nodes(); ++i)
    if (m.rest[static_cast<std::size_t>(i)].x() + 1e-3 * m.rest[static_cast<std::size_t>(i)].y() >
        m.rest[static_cast<std::size_t>(tip)].x() +
            1e-3 * m.rest[static_cast<std::size_t>(tip)].y())
      tip = i;
  return tip;
}

// Grasper pointing down (-y) onto the beam's free end: local z = -y, local x = +x, pin = +z.
// Quaternion of that frame: rotation about x by +90 degrees.
const std::string kDown = "0.7071067811865476,0.7071067811865476,0,0";

// A grasper over the beam's end, jaw tips 3 mm into it (top at y = 5 mm): open, close (t = 0.05),
// lift 5 mm (t = 0.15), open (t = 0.20).
std::unique_ptr<BeamRun> grab_lift_release(const fs::path& dir) {
  const std::string csv =
      "0.00,grasper,0.095,0.002,0," + kDown + ",0.9\n" + "0.02,grasper,0.095,0.002,0," + kDown +
      ",0.9\n" + "0.05,grasper,0.095,0.002,0," + kDown + ",0.0\n" + "0.15,grasper,0.095,0.007,0," +
      kDown + ",0.0\n" + "0.20,grasper,0.095,0.007,0," + kDown + ",0.9\n";
  const std::string tool =
      "[[tool]]\nname = \"grasper\"\nkind = \"grasper\"\ndevice = \"script:path.csv\"\n";
  return beam_with_tools(dir, "\"fem\", \"surface\", \"contact\"", tool, csv);
}

TEST(Grasper, GrabsLiftsAndLetsGo) {
  const fs::path dir = out_dir("grasper");
  auto run = grab_lift_release(dir);
  ASSERT_NE(run->comp.contact, nullptr);
  SimState& s = run->assembled.state;
  const std::vector<std::uint8_t> fixed0 = s.mesh.fixed;
  const std::int32_t tip = tip_node(s.mesh);
  const double y0 = s.mesh.x[static_cast<std::size_t>(tip)].y();
  run->comp.runner->run(s, 30);  // t = 0.15: closed and lifted
  const std::size_t held = contact::grasped_counts(run->assembled.state)[0];
  EXPECT_GE(held, 3u);  // the beam's top nodes at x = 9, 9.5 and 10 cm
  EXPECT_GT(s.mesh.x[static_cast<std::size_t>(tip)].y(), y0 + 0.002);  // the end came up
  EXPECT_GT(s.events.tool_force_n[0].y(), 0.0);                        // it pulls the tissue up
  run->comp.runner->run(s, 12);                                        // t = 0.21: opened
  EXPECT_EQ(contact::grasped_counts(run->assembled.state)[0], 0u);
  EXPECT_EQ(s.mesh.fixed, fixed0);
  const auto m = run->comp.metrics->report();
  EXPECT_NEAR(m["path_length_m"]["grasper"].get<double>(), 0.005, 1e-9);
  EXPECT_GT(m["force_max_n"]["grasper"].get<double>(), 0.0);
  EXPECT_GT(m["peak_stress_pa"].get<double>(), 0.0);
}

// Two graspers on the beam's end: one takes it, the other takes it too, the first lets go (a
// hand-to-hand transfer), the second lets go. Whichever lets go first, the nodes stay held while
// either holds them, and every node gets its own Dirichlet flag back at the end.
TEST(Grasper, TwoGraspersHandTissueOverAndEveryNodeGetsItsFlagBack) {
  for (const bool first_lets_go_first : {true, false}) {
    SCOPED_TRACE(first_lets_go_first);
    const fs::path dir = out_dir("grasper_handover");
    auto row = [&](const char* tool, double t, double jaw) {
      char line[160];
      std::snprintf(line, sizeof line, "%.3f,%s,0.095,0.002,0,%s,%.1f\n", t, tool, kDown.c_str(),
                    jaw);
      return std::string(line);
    };
    const double a_open = first_lets_go_first ? 0.12 : 0.16;
    const double b_open = first_lets_go_first ? 0.16 : 0.12;
    const std::string csv = row("a", 0.0, 0.9) + row("a", 0.02, 0.9) + row("a", 0.05, 0.0) +
                            row("a", a_open - 0.01, 0.0) + row("a", a_open, 0.9) +
                            row("b", 0.0, 0.9) + row("b", 0.05, 0.9) + row("b", 0.08, 0.0) +
                            row("b", b_open - 0.01, 0.0) + row("b", b_open, 0.9);
    std::string tools;
    for (const char* name : {"a", "b"})
      tools += std::string("[[tool]]\nname = \"") + name +
               "\"\nkind = \"grasper\"\ndevice = \"script:path.csv\"\n";
    auto run = beam_with_tools(dir, "\"fem\", \"surface\", \"contact\"", tools, csv);
    SimState& s = run->assembled.state;
    const std::vector<std::uint8_t> fixed0 = s.mesh.fixed;
    run->comp.runner->run(s, 20);  // t = 0.1: both hold
    const auto counts = contact::grasped_counts(run->assembled.state);
    ASSERT_GE(counts[0], 3u);
    ASSERT_GE(counts[1], 3u);
    run->comp.runner->run(s, 6);  // t = 0.13: one has let go, the other holds
    const std::size_t holder = first_lets_go_first ? 1 : 0;
    ASSERT_EQ(contact::grasped_counts(run->assembled.state)[1 - holder], 0u);
    ASSERT_GE(contact::grasped_counts(run->assembled.state)[holder], 3u);
    for (std::int32_t v : s.shared.grasped[holder])
      EXPECT_EQ(s.mesh.fixed[static_cast<std::size_t>(v)], 1) << "node " << v;
    run->comp.runner->run(s, 8);  // t = 0.17: both have let go
    EXPECT_EQ(contact::grasped_counts(run->assembled.state)[holder], 0u);
    EXPECT_EQ(s.mesh.fixed, fixed0);
  }
}

// Tears: each time the peak stress rises above the scene's tear stress. The grasper's lift
// stresses the beam; a tear stress under that peak counts one tear, while it is lifted; one over
// it counts none. The rubric may score `tears` only where the scene sets a tear stress.
TEST(Grasper, LiftingHarderThanTheTissueBearsCountsATear) {
  const fs::path dir = out_dir("grasper_tears");
  const std::string csv =
      "0.00,grasper,0.095,0.002,0," + kDown + ",0.9\n" + "0.02,grasper,0.095,0.002,0," + kDown +
      ",0.9\n" + "0.05,grasper,0.095,0.002,0," + kDown + ",0.0\n" + "0.15,grasper,0.095,0.007,0," +
      kDown + ",0.0\n" + "0.20,grasper,0.095,0.007,0," + kDown + ",0.9\n";
  auto run_with = [&](const std::string& metrics) {
    const std::string tool = metrics +
                             "[[tool]]\nname = \"grasper\"\nkind = \"grasper\"\n"
                             "device = \"script:path.csv\"\n";
    auto run = beam_with_tools(dir, "\"fem\", \"surface\", \"contact\"", tool, csv);
    run->comp.runner->run(run->assembled.state, 44);  // lifted, then let go
    return run->comp.metrics->report();
  };
  const double peak = run_with("")["peak_stress_pa"].get<double>();
  ASSERT_GT(peak, 0.0);
  const auto torn = run_with("[metrics]\ntear_stress = " + std::to_string(0.5 * peak) + "\n");
  EXPECT_EQ(torn["tears"].get<int>(), 1) << torn.dump();
  EXPECT_GT(torn["tear_times_s"][0].get<double>(), 0.05);  // after the grasp
  const auto whole = run_with("[metrics]\ntear_stress = " + std::to_string(2.0 * peak) + "\n");
  EXPECT_EQ(whole["tears"].get<int>(), 0);
  EXPECT_FALSE(run_with("").contains("tears"));
}

// The stage with the haptic loop's reactions on, taking over `from`'s grasps (the run's state's).
std::unique_ptr<contact::ToolContactStage> reacting_copy(const BeamRun& run,
                                                         const contact::ToolContactStage* from) {
  auto probe = std::make_unique<contact::ToolContactStage>(
      run.scene, lame_table(run.scene, run.assembled), contact::ContactOutputs{true, false});
  if (from != nullptr) {
    SimState copy = run.assembled.state;
    probe->adopt(copy);
  }
  return probe;
}

TEST(Grasper, TheHapticLoopFeelsTheHeldTissuesPull) {
  const fs::path dir = out_dir("grasper_pull");
  auto run = grab_lift_release(dir);
  SimState& s = run->assembled.state;
  run->comp.runner->run(s, 30);  // closed and lifted 5 mm
  ASSERT_GE(contact::grasped_counts(run->assembled.state)[0], 3u);
  auto probe = reacting_copy(*run, run->comp.contact);
  SimState copy = s;
  probe->step(StepContext{30, s.time_s, 0.005}, copy);
  ASSERT_EQ(copy.events.tool_reactions.size(), 1u);
  const Vec3 pull = copy.events.tool_reactions[0].held_pull_n;
  // The lifted end pulls the jaws back down; it is what the grasper pulls the tissue with,
  // reversed (the shaft touches nothing here).
  EXPECT_LT(pull.y(), 0.0);
  EXPECT_LT((pull + copy.events.tool_force_n[0]).norm(), 1e-12 * pull.norm());
  EXPECT_EQ(copy.events.tool_reactions[0].jaw_torque_nm, 0.0);
}

// An exchange withdraws a grasper holding tissue into its port: it lets go (the held nodes are
// free again as they were), and it touches nothing, so no force, no contact plane, no reaction.
TEST(Grasper, WithdrawnIntoItsPortItLetsGoAndTouchesNothing) {
  const fs::path dir = out_dir("grasper_withdrawn");
  auto run = grab_lift_release(dir);
  SimState& s = run->assembled.state;
  const std::vector<std::uint8_t> fixed_before = s.mesh.fixed;
  run->comp.runner->run(s, 30);  // closed and lifted 5 mm
  ASSERT_GE(contact::grasped_counts(run->assembled.state)[0], 3u);
  auto probe = reacting_copy(*run, run->comp.contact);
  SimState copy = s;
  // Its port far from the beam, and then (a property over placements) anywhere near it: an
  // instrument in its port ignores where its pose says it is.
  std::mt19937 rng(4);
  std::uniform_real_distribution<double> u(-0.05, 0.05);
  for (int k = 0; k < 50; ++k) {
    copy.tools[0] = port_pose(Vec3(u(rng), u(rng), u(rng)), Vec3(0.0, 0.0, -1.0));
    probe->step(StepContext{30 + static_cast<std::uint64_t>(k), s.time_s, 0.005}, copy);
    EXPECT_EQ(contact::grasped_counts(copy)[0], 0u) << k;
    EXPECT_EQ(copy.events.tool_force_n[0].norm(), 0.0) << k;
    EXPECT_TRUE(copy.events.external_force_n.empty()) << k;
    EXPECT_FALSE(copy.events.contact_planes[0]) << k;
    EXPECT_EQ(copy.events.tool_reactions[0].held_pull_n.norm(), 0.0) << k;
    EXPECT_EQ(copy.mesh.fixed, fixed_before) << k;  // the grasp's Dirichlet nodes are free again
  }
}

TEST(Contact, TheHapticLoopFeelsTheTissuePushingOnTheShaft) {
  const fs::path dir = out_dir("shaft_push");
  // A closed grasper's shaft across the top of the beam at x = 8 cm, 1 mm deep (as in
  // Contact.ShaftPressesTheBeamDownAndTwoToolsActAtOnce), its port 20 cm up the shaft.
  const std::string csv = "0,left,0.08,0.0065,-0.025,0,0,1,0,0\n";
  const std::string tools =
      "[[tool]]\nname = \"left\"\nkind = \"grasper\"\ndevice = \"script:path.csv\"\n"
      "trocar = [0.08, 0.0065, 0.2]\n";
  auto run = beam_with_tools(dir, "\"fem\", \"surface\", \"contact\"", tools, csv);
  auto probe = reacting_copy(*run, nullptr);
  SimState s = run->assembled.state;
  run->comp.runner->step(s);  // the script poses the tool
  probe->step(StepContext{1, s.time_s, 0.005}, s);
  const ToolReaction& r = s.events.tool_reactions[0];
  // The beam pushes the shaft up, as hard as the shaft pushes it down (the jaws, beyond the
  // beam, touch nothing), where it crosses the beam: 20 of the 22.5 cm from port to tip.
  EXPECT_GT(r.shaft_push_n.y(), 0.0);
  EXPECT_LT((r.shaft_push_n + s.events.tool_force_n[0]).norm(), 1e-12 * r.shaft_push_n.norm());
  EXPECT_NEAR(r.shaft_lever, 0.2 / 0.225, 0.03);
  EXPECT_EQ(r.held_pull_n.norm(), 0.0);
}

TEST(Scissors, TissueBetweenClosingBladesResistsUntilTheStrokeIsCut) {
  const fs::path dir = out_dir("scissors_resist");
  const std::string tool =
      "[[tool]]\nname = \"scissors\"\nkind = \"scissors\"\ndevice = \"script:path.csv\"\n";
  auto run = beam_with_tools(dir, "\"fem\", \"surface\", \"contact\"", tool,
                             "0,scissors,0.05,0.05,0," + kDown + ",0\n");
  auto probe = reacting_copy(*run, nullptr);
  SimState s = run->assembled.state;
  // Pointing down across the beam's top at x = 5 cm, blades opening along the beam, reaching
  // 8 mm into it.
  const auto torque_at = [&](double jaw, bool cut) {
    s.tools[0].tip_m = {0.05, -0.003, 0.0};
    s.tools[0].quat_wxyz = {0.7071067811865476, 0.7071067811865476, 0.0, 0.0};
    s.tools[0].jaw_rad = jaw;
    s.events.cuts.clear();
    if (cut) {
      CutEvent e;
      e.tool = 0;
      s.events.cuts.push_back(e);
    }
    probe->step(StepContext{0, 0.0, 0.005}, s);
    return s.events.tool_reactions[0].jaw_torque_nm;
  };
  EXPECT_EQ(torque_at(1.0, false), 0.0);  // opened: nothing to resist
  const double part = torque_at(0.6, false);
  EXPECT_GT(part, 0.0);
  EXPECT_GE(torque_at(0.3, false), part);
  EXPECT_GT(torque_at(0.0, false), part);  // closed on all the tissue in reach (5 mm nodes)
  EXPECT_EQ(torque_at(0.0, true), 0.0);    // the stroke was cut: the tissue gave way
  EXPECT_EQ(torque_at(0.0, false), 0.0);   // and stays given
  EXPECT_EQ(torque_at(0.8, false), 0.0);   // opened again
  EXPECT_GT(torque_at(0.5, false), 0.0);   // a new stroke
}

// The "plasticity" effect: the grasper lifts the beam's end 5 mm, holds it (t = 0.05-0.5 s) and
// lets go. Elastic tissue springs back; tissue that yields keeps part of the lift (permanent
// set), measured as the mean offset of the end over its last 0.5 s of free motion.
double set_after_lift(const std::string& name, bool plastic) {
  const fs::path dir = out_dir(name);
  const std::string csv =
      "0.00,grasper,0.095,0.002,0," + kDown + ",0.9\n" + "0.02,grasper,0.095,0.002,0," + kDown +
      ",0.9\n" + "0.05,grasper,0.095,0.002,0," + kDown + ",0.0\n" + "0.15,grasper,0.095,0.007,0," +
      kDown + ",0.0\n" + "0.50,grasper,0.095,0.007,0," + kDown + ",0.0\n" +
      "0.55,grasper,0.095,0.007,0," + kDown + ",0.9\n";
  const std::string tool =
      "[[tool]]\nname = \"grasper\"\nkind = \"grasper\"\ndevice = \"script:path.csv\"\n";
  auto run =
      beam_with_tools(dir,
                      plastic ? "\"fem\", \"surface\", \"contact\", \"plasticity\""
                              : "\"fem\", \"surface\", \"contact\"",
                      tool, csv, "plasticity = { yield = 0.002, creep = 20.0, max = 0.5 }\n");
  const auto& simulated = run->comp.built;
  EXPECT_EQ(std::find(simulated.begin(), simulated.end(), Effect::kPlasticity) != simulated.end(),
            plastic);
  SimState& s = run->assembled.state;
  const auto tip = static_cast<std::size_t>(tip_node(s.mesh));
  run->comp.runner->run(s, 500);  // let go at 0.55 s, free until 2.5 s
  double offset = 0.0;
  for (int k = 0; k < 100; ++k) {
    run->comp.runner->step(s);
    offset += (s.mesh.x[tip].y() - s.mesh.rest[tip].y()) / 100.0;
  }
  return offset;
}

TEST(Plasticity, TissueThatYieldsKeepsAPermanentSet) {
  const double elastic = set_after_lift("plasticity_off", false);
  const double plastic = set_after_lift("plasticity_on", true);
  EXPECT_GT(plastic, 5e-4);                     // part of the 5 mm lift stays
  EXPECT_LT(std::abs(elastic), 0.2 * plastic);  // elastic tissue springs back
}

// The held nodes move with the jaws between steps (Dirichlet): that is the tool's work, not a
// gain of the solve, so the FEM's divergence guard must not flag it (a flagged step reports
// "not converged" and starts its solve cold). With CHOLMOD every solve is exact, so no step of
// a grab, lift and release may be flagged.
TEST(Grasper, MovingTheHeldNodesIsNotAnEnergyGainOfTheSolve) {
  const fs::path dir = out_dir("grasper_energy");
  auto run = grab_lift_release(dir);
  ASSERT_NE(run->comp.fem, nullptr);
  SimState& s = run->assembled.state;
  int held_steps = 0, flagged = 0;
  for (int k = 0; k < 45; ++k) {
    run->comp.runner->run(s, 1);
    held_steps += contact::grasped_counts(run->assembled.state)[0] > 0 ? 1 : 0;
    const fem::StepStatus& st = run->comp.fem->last_status();
    flagged += st.energy_gain ? 1 : 0;
    EXPECT_TRUE(st.converged) << "step " << k;
  }
  EXPECT_GT(held_steps, 15);  // it did grab and lift
  EXPECT_EQ(flagged, 0);
}

TEST(Contact, ShaftPressesTheBeamDownAndTwoToolsActAtOnce) {
  const fs::path dir = out_dir("contact");
  // A closed grasper held still, its shaft (radius 2.5 mm) lying across the top of the beam
  // (y = 5 mm) at x = 8 cm, 1 mm deep, pointing along -z (jaws beyond the beam); scissors held
  // clear of it at the same time.
  const std::string along_minus_z = "0,0,1,0";
  const std::string csv = "0,left,0.08,0.0065,-0.025," + along_minus_z + ",0\n" +
                          "0,right,0.05,0.05,0," + kDown + ",0\n";
  const std::string tools =
      "[[tool]]\nname = \"left\"\nkind = \"grasper\"\ndevice = \"script:path.csv\"\n"
      "trocar = [0.08, 0.0065, 0.2]\n"
      "[[tool]]\nname = \"right\"\nkind = \"scissors\"\ndevice = \"script:path.csv\"\n";
  auto pressed = beam_with_tools(dir, "\"fem\", \"surface\", \"contact\"", tools, csv);
  SimState& s = pressed->assembled.state;
  const std::int32_t tip = tip_node(s.mesh);
  const double tip_y0 = s.mesh.x[static_cast<std::size_t>(tip)].y();
  // The shaft pushes the weightless beam down and away: contact while it touches, none after.
  std::int64_t touching_steps = 0;
  for (int k = 0; k < 20; ++k) {
    pressed->comp.runner->step(s);
    const auto& f = s.events.tool_force_n;
    if (pressed->comp.contact->contacts() > 0) {
      ++touching_steps;
      EXPECT_LT(f[0].y(), 0.0) << "step " << k;  // pushes down
    }
    EXPECT_EQ(f[1].norm(), 0.0) << "step " << k;  // the scissors touch nothing
  }
  EXPECT_GE(touching_steps, 5);
  EXPECT_LT(s.mesh.x[static_cast<std::size_t>(tip)].y() - tip_y0, -1e-4);  // the end went down
  for (const Vec3& x : s.mesh.x) EXPECT_TRUE(x.allFinite());
  // Without "contact" the same tools do nothing to the (weightless) beam.
  const fs::path dir2 = out_dir("contact_off");
  auto free_run = beam_with_tools(dir2, "\"fem\"", tools, csv);
  EXPECT_EQ(free_run->comp.contact, nullptr);
  free_run->comp.runner->run(free_run->assembled.state, 20);
  double moved = 0.0;
  for (std::size_t i = 0; i < free_run->assembled.state.mesh.x.size(); ++i)
    moved = std::max(
        moved,
        (free_run->assembled.state.mesh.x[i] - free_run->assembled.state.mesh.rest[i]).norm());
  EXPECT_LT(moved, 1e-12);
}

}  // namespace
}  // namespace serosa::app
