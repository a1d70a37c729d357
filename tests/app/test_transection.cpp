// End to end: the default appendectomy scene, headless, with scissors closing across the appendix
// (config/paths/appendix_transection.csv). The appendix ends in two pieces, every cut passes the
// cutting invariant checker, FEM and surface follow the cuts incrementally, the report is written.
#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <random>
#include <sstream>
#include <string>
#include <utility>
#include <vector>

#include "app/headless.h"
#include "app_test_util.h"
#include "cutting/validate.h"
#include "engine/io/mesh_io.h"
#include "engine/mesh_check.h"
#include "engine/tool_geometry.h"

namespace serosa::app {
namespace {

using namespace serosa::app::testing;

// The run cut the appendix in two in one stroke, with the cut invariants and the volume kept, no
// tet below quality 1e-3 and at most `growth` times the tets it began with.
void expect_transected_in_one_stroke(const nlohmann::json& report, const fs::path& final_mesh,
                                     double growth) {
  const auto& cut = report["cutting"];
  EXPECT_EQ(cut["strokes"].get<int>(), 1);
  EXPECT_EQ(cut["invalid"].get<int>(), 0) << cut["problems"].dump(1);
  EXPECT_EQ(cut["per_stroke"].back()["pinned"].get<int>(), 0);
  EXPECT_GT(report["cut_steps"].back()["ms"].get<double>(), 0.0);  // the cut step is timed
  EXPECT_NEAR(report["mesh_final"]["rest_volume_m3"].get<double>(),
              report["mesh_initial"]["rest_volume_m3"].get<double>(),
              1e-9 * report["mesh_initial"]["rest_volume_m3"].get<double>());
  EXPECT_GE(report["mesh_final"]["min_quality"].get<double>(), 1e-3);
  EXPECT_LE(report["mesh_final"]["tets"].get<double>(),
            growth * report["mesh_initial"]["tets"].get<double>());
  const TetMesh after = read_mesh(final_mesh);
  EXPECT_EQ(cutting::count_components(after, 1), 2);
  EXPECT_TRUE(check_mesh(after).valid);
}

TEST(Transection, ScissorsCutTheAppendixInTwo) {
  const fs::path dir = out_dir("transection");
  HeadlessOptions o;
  o.scene = source("config/transection.toml");
  o.tool_path = source("config/paths/appendix_transection.csv");
  o.steps = 30;  // the jaws close over steps 4..24
  o.validate_cuts = true;
  o.report = dir / "report.json";
  o.export_final = dir / "final.msh";
  o.progress = false;
  const auto report = run_headless(o);

  // The report is written and says what happened.
  ASSERT_TRUE(fs::exists(dir / "report.json"));
  const auto& cut = report["cutting"];
  EXPECT_GT(cut["cuts"].get<int>(), 0);
  EXPECT_EQ(cut["strokes"].get<int>(), 1);  // one closing stroke, cut as one sector
  EXPECT_EQ(cut["validated"], cut["cuts"]);
  EXPECT_EQ(cut["invalid"].get<int>(), 0) << cut["problems"].dump(1);
  EXPECT_EQ(cut["degenerate_tets"].get<int>(), 0);
  EXPECT_GT(report["mesh_final"]["tets"].get<int>(), report["mesh_initial"]["tets"].get<int>());
  EXPECT_TRUE(report["mesh_final"]["valid"].get<bool>());
  // Rest volume is conserved by cutting.
  EXPECT_NEAR(report["mesh_final"]["rest_volume_m3"].get<double>(),
              report["mesh_initial"]["rest_volume_m3"].get<double>(),
              1e-9 * report["mesh_initial"]["rest_volume_m3"].get<double>());
  // FEM and surface took the deltas incrementally, and FEM kept stepping.
  EXPECT_GT(report["surface"]["updates"].get<int>(), 0);
  EXPECT_EQ(report["surface"]["failed_updates"].get<int>(), 0);
  EXPECT_EQ(report["surface"]["rebuilds"].get<int>(), 0);  // the assembled state brings the first
  EXPECT_EQ(report["fem"]["rejected"].get<int>(), 0);
  // The scissors pressed on the tissue they closed on: the blades' shear load, above zero and
  // below the firmest tissue's strength over the widest wedge a blade can sweep (1 rad,
  // contact/blade_resistance.h), 3e4 Pa x 0.5 x L^2.
  const double scissors_n = report["metrics"]["force_max_n"]["scissors"].get<double>();
  EXPECT_GT(scissors_n, 0.1);
  EXPECT_LT(scissors_n, 3e4 * 0.5 * kJawLength * kJawLength);

  // The appendix (group 1) is in two pieces; before the cut it was one.
  const TetMesh before = read_mesh(source("assets/appendectomy_coarse.msh"));
  EXPECT_EQ(cutting::count_components(before, 1), 1);
  const TetMesh after = read_mesh(dir / "final.msh");
  EXPECT_EQ(cutting::count_components(after, 1), 2);
  EXPECT_TRUE(check_mesh(after).valid);
}

void replace_all(std::string& s, const std::string& from, const std::string& to) {
  for (auto at = s.find(from); at != std::string::npos; at = s.find(from, at + to.size()))
    s.replace(at, from.size(), to);
}

// The default scene's text with `from` replaced by `to`, written to dir / name with its relative
// paths made absolute.
fs::path default_scene_with(const fs::path& dir, const std::string& name, const std::string& from,
                            const std::string& to) {
  std::string text;
  {
    std::ifstream in(source("config/transection.toml"));
    std::ostringstream all;
    all << in.rdbuf();
    text = all.str();
  }
  const auto at = text.find(from);
  EXPECT_NE(at, std::string::npos) << from;
  if (at != std::string::npos) text.replace(at, from.size(), to);
  std::string assets = "\"";
  assets.append(source("assets").string()).append("/");
  std::string paths = "script:";
  paths.append(source("config/paths").string()).append("/");
  replace_all(text, "\"../assets/", assets);
  replace_all(text, "script:paths/", paths);
  std::string rubric = "\"";
  rubric.append(source("config/assessment").string()).append("/");
  replace_all(text, "\"assessment/", rubric);
  const fs::path scene = dir / name;
  { std::ofstream(scene) << text; }
  return scene;
}

TEST(Transection, TheScenesCuttingMethodCutsRemoveDropsTets) {
  // [cutting] method = "remove": the same stroke deletes the tets the blade crosses, adds none.
  const fs::path dir = out_dir("remove_method");
  HeadlessOptions o;
  o.scene = default_scene_with(dir, "remove.toml", "method = \"pattern\"", "method = \"remove\"");
  o.tool_path = source("config/paths/appendix_transection.csv");
  o.steps = 30;
  o.progress = false;
  const auto report = run_headless(o);
  const auto& cut = report["cutting"];
  EXPECT_GT(cut["cuts"].get<int>(), 0);
  EXPECT_GT(cut["tets_removed"].get<int>(), 0);
  EXPECT_EQ(cut["tets_added"].get<int>(), 0);
  EXPECT_EQ(cut["nodes_added"].get<int>(), 0);
  EXPECT_LT(report["mesh_final"]["tets"].get<int>(), report["mesh_initial"]["tets"].get<int>());
  EXPECT_LT(report["mesh_final"]["rest_volume_m3"].get<double>(),
            report["mesh_initial"]["rest_volume_m3"].get<double>());
}

TEST(Transection, SceneWithoutCuttingNeverCuts) {
  // The same scissors motion on a scene that does not list "cutting": no cutting state at all.
  const fs::path dir = out_dir("no_cutting");
  HeadlessOptions o;
  o.scene = default_scene_with(dir, "no_cutting.toml", "\"cutting\", ", "");
  o.tool_path = source("config/paths/appendix_transection.csv");
  o.steps = 30;
  o.progress = false;
  const auto report = run_headless(o);
  EXPECT_FALSE(report.contains("cutting"));
  EXPECT_EQ(report["mesh_final"]["tets"], report["mesh_initial"]["tets"]);
  EXPECT_FALSE(report["time_per_stage_ms"].contains("cutting"));
}

// The transection's path with the scissors' jaw angles (rad) at the given times (s) between the
// opening at 0.02 s and the closed jaws at the last time: pauses, or a close in a few steps.
fs::path closing_path(const fs::path& dir, const std::string& name,
                      const std::vector<std::pair<double, double>>& jaw_at) {
  const std::string pose = "0.07217,-0.05211,-0.00455,0.081435,0.902719,0.373918,-0.196600,";
  std::ostringstream csv;
  csv << "t,tool,px,py,pz,qw,qx,qy,qz,jaw\n"
      << "0.000,endoscope,0.0385,-0.0154,0.1110,0.029262,0.002558,0.995772,-0.087040,0.00\n"
      << "0.000,grasper,0.0300,-0.0200,0.0600,0.324226,0.014191,0.944968,-0.041360,0.00\n"
      << "0.000,scissors," << pose << "1.00\n0.020,scissors," << pose << "1.00\n";
  for (const auto& [t, jaw] : jaw_at) csv << t << ",scissors," << pose << jaw << "\n";
  csv << "0.400,scissors," << pose << "0.00\n"
      << "0.400,grasper,0.0300,-0.0200,0.0600,0.324226,0.014191,0.944968,-0.041360,0.00\n"
      << "0.400,endoscope,0.0385,-0.0154,0.1110,0.029262,0.002558,0.995772,-0.087040,0.00\n";
  const fs::path path = dir / name;
  { std::ofstream(path) << csv.str(); }
  return path;
}

// Jaws that pause while they close, or close in a few steps with pauses between, without moving:
// one stroke, cut once when the jaws have closed, like the uninterrupted close. Cut at the pause,
// the two blades' sectors left a notch that the rest of the closing cut next to them: the appendix
// stayed in one piece after a pause at 0.65 rad, with a tet of quality 6e-4.
TEST(Transection, PausesWhileClosingCutTheAppendixInOneStroke) {
  const fs::path dir = out_dir("transection_pauses");
  const std::vector<std::vector<std::pair<double, double>>> closings = {
      {{0.07, 0.35}, {0.15, 0.35}, {0.20, 0.0}},
      {{0.07, 0.65}, {0.15, 0.65}, {0.20, 0.0}},
      {{0.05, 0.75}, {0.09, 0.75}, {0.12, 0.5}, {0.20, 0.5}, {0.23, 0.25}, {0.30, 0.0}},
  };
  for (std::size_t k = 0; k < closings.size(); ++k) {
    SCOPED_TRACE("closing " + std::to_string(k));
    HeadlessOptions o;
    o.scene = source("config/transection.toml");
    o.tool_path = closing_path(dir, "closing" + std::to_string(k) + ".csv", closings[k]);
    o.steps = 80;
    o.validate_cuts = true;
    o.export_final = dir / ("final" + std::to_string(k) + ".msh");
    o.progress = false;
    const auto report = run_headless(o);
    EXPECT_EQ(report["cutting"]["cuts"].get<int>(), 1);
    expect_transected_in_one_stroke(report, dir / ("final" + std::to_string(k) + ".msh"), 1.1);
  }
}

// How the scissors move while they close over the default scene's appendix.
struct Closing {
  std::string name;
  Vec3 drift = Vec3::Zero();  // hinge displacement over the close (side, forward, pin), m
  double roll = 0.0;          // turn about the shaft over the close, rad
  double tremor = 0.0;        // random displacement of every sample, m
  double duration = 0.1;      // s, from open (1 rad) to closed
  double reopen_at = -1.0;    // close to this angle, open by 0.3 rad, then close
};

// The transection's path with the scissors closing from 0.02 s in `c.duration`, a sample every
// 5 ms, moving as `c` says.
fs::path moving_path(const fs::path& dir, const Closing& c) {
  const Vec3 tip0(0.07217, -0.05211, -0.00455);
  const Eigen::Quaterniond q0(0.081435, 0.902719, 0.373918, -0.196600);
  const Mat3 r0 = q0.normalized().toRotationMatrix();
  const Vec3 side = r0.col(0), pin = r0.col(1), forward = r0.col(2);
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  std::ostringstream csv;
  csv.precision(9);
  csv << "t,tool,px,py,pz,qw,qx,qy,qz,jaw\n"
      << "0.000,endoscope,0.0385,-0.0154,0.1110,0.029262,0.002558,0.995772,-0.087040,0.00\n"
      << "0.000,grasper,0.0300,-0.0200,0.0600,0.324226,0.014191,0.944968,-0.041360,0.00\n";
  const auto sample = [&](double t, double s, double jaw) {
    const Eigen::Quaterniond q = Eigen::Quaterniond(Eigen::AngleAxisd(s * c.roll, forward)) * q0;
    const Vec3 hinge0 = tip0 - kJawLength * forward;
    const Vec3 hinge = hinge0 +
                       s * (c.drift.x() * side + c.drift.y() * forward + c.drift.z() * pin) +
                       c.tremor * Vec3(u(rng), u(rng), u(rng));
    const Vec3 tip = hinge + kJawLength * (q.normalized().toRotationMatrix().col(2));
    csv << t << ",scissors," << tip.x() << "," << tip.y() << "," << tip.z() << "," << q.w() << ","
        << q.x() << "," << q.y() << "," << q.z() << "," << jaw << "\n";
  };
  sample(0.0, 0.0, 1.0);
  const int n = static_cast<int>(std::lround(c.duration / 0.005));
  for (int k = 0; k <= n; ++k) {
    const double s = static_cast<double>(k) / n;
    double jaw = 1.0 - s;
    if (c.reopen_at >= 0.0) {  // down to reopen_at by s = 0.4, up 0.3 by 0.5, then closed
      jaw = s < 0.4   ? 1.0 - (1.0 - c.reopen_at) * s / 0.4
            : s < 0.5 ? c.reopen_at + 0.3 * (s - 0.4) / 0.1
                      : (c.reopen_at + 0.3) * (1.0 - (s - 0.5) / 0.5);
    }
    sample(0.02 + k * 0.005, s, std::max(jaw, 0.0));
  }
  sample(0.02 + n * 0.005 + 0.1, 1.0, 0.0);
  const fs::path path = dir / (c.name + ".csv");
  { std::ofstream(path) << csv.str(); }
  return path;
}

// Every closing motion a hand makes transects the appendix in one stroke (a second bite at the
// same place included), with at most 1.5x its tets, quality >= 1e-3, the volume
// kept, and no pinned tet in the through-cut. Cut step by step, moving 2 mm sideways left the
// appendix in one piece with 46 % more tets, 3 mm along the shaft in one piece with 4.2x the tets,
// and rolling grew it 90-fold.
TEST(Transection, MovingScissorsCutTheAppendixInOneStroke) {
  const fs::path dir = out_dir("transection_moving");
  const std::vector<Closing> closings = {
      {"forward", Vec3(0, 3e-3, 0)},
      {"back", Vec3(0, -1.5e-3, 0)},
      {"sideways", Vec3(2e-3, 0, 0)},
      {"across", Vec3(0, 0, 1e-3)},
      {"roll", Vec3::Zero(), 0.25},
      {"roll_wide", Vec3::Zero(), 1.2},
      {"roll_half_turn", Vec3::Zero(), 3.0},
      {"tremor", Vec3::Zero(), 0.0, 0.4e-3},
      {"tremor_sideways", Vec3(2e-3, 1e-3, 0), 0.0, 0.8e-3},
      {"slow", Vec3(1e-3, 1e-3, 0.5e-3), 0.0, 0.0, 0.6},
      {"reopen", Vec3(1e-3, 0, 0), 0.0, 0.0, 0.2, 0.5},
  };
  const TetMesh before = read_mesh(source("assets/appendectomy_coarse.msh"));
  for (const Closing& c : closings) {
    SCOPED_TRACE(c.name);
    HeadlessOptions o;
    o.scene = source("config/transection.toml");
    o.tool_path = moving_path(dir, c);
    o.steps = static_cast<std::uint64_t>(std::lround((c.duration + 0.15) / 0.005));
    o.validate_cuts = true;
    o.export_final = dir / (c.name + ".msh");
    o.progress = false;
    const auto report = run_headless(o);
    const auto& last = report["cutting"]["per_stroke"].back();
    EXPECT_GT(last["crack_area_m2"].get<double>(), 0.9 * last["swept_area_m2"].get<double>());
    // Never farther from the blades' path in the tissue than the samples from their plane; a
    // stroke that rolls (up to 1.2 rad) or drifts across the blade plane is cut along its swept
    // surface, at most 0.6 of that away (cut in the plane: 0.46-0.98 of it, docs/BENCHMARKS.md).
    const double deviation = last["deviation_m"].get<double>();
    EXPECT_LE(last["crack_deviation_m"].get<double>(), deviation + 1e-12);
    if (c.name == "across" || c.name == "roll" || c.name == "roll_wide" || c.name == "slow") {
      EXPECT_TRUE(last["bent"].get<bool>());
      EXPECT_LE(last["crack_deviation_m"].get<double>(), 0.6 * deviation);
    }
    expect_transected_in_one_stroke(report, dir / (c.name + ".msh"), 1.5);
  }
}

// The default procedure with the grasper, which holds the appendix from 1.8 s, pulling it 3 mm
// while the scissors close (3.0-3.3 s): the tissue moves under the blades, and the stroke, pinned
// to the tissue it swept, still separates it along one crack.
TEST(Transection, AGrasperPullingWhileTheScissorsCloseStillTransects) {
  const fs::path dir = out_dir("transection_pull");
  std::ifstream in(source("config/paths/appendectomy.csv"));
  std::ostringstream csv;
  const std::string held = "0.07909,-0.05534,-0.00153,0.221251,0.886205,0.311960,0.261474,0.00";
  const std::string pulled = "0.08209,-0.05534,-0.00153,0.221251,0.886205,0.311960,0.261474,0.00";
  int replaced = 0;
  for (std::string line; std::getline(in, line);) {
    if (line.rfind("3.500,grasper,", 0) == 0) {
      line = "3.500,grasper," + pulled;
      ++replaced;
    }
    csv << line << "\n";
    if (line.rfind("3.000,scissors,", 0) == 0) {
      csv << "3.000,grasper," << held << "\n3.300,grasper," << pulled << "\n";
      ++replaced;
    }
  }
  ASSERT_EQ(replaced, 2) << "the default path changed: update this test";
  const fs::path path = dir / "pull.csv";
  { std::ofstream(path) << csv.str(); }
  HeadlessOptions o;
  o.scene = source("config/transection.toml");
  o.tool_path = path;
  o.steps = 680;
  o.validate_cuts = true;
  o.export_final = dir / "final.msh";
  o.progress = false;
  const auto report = run_headless(o);
  // The tissue moved under the blades: the swept samples, carried with it, bend off one plane.
  EXPECT_GT(report["cutting"]["per_stroke"].back()["deviation_m"].get<double>(), 0.3e-3);
  expect_transected_in_one_stroke(report, dir / "final.msh", 1.5);
}

}  // namespace
}  // namespace serosa::app
