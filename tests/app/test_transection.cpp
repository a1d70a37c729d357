// End to end: the default appendectomy scene, headless, with scissors closing across the appendix
// (config/paths/appendix_transection.csv). The appendix ends in two pieces, every cut passes the
// cutting invariant checker, FEM and surface follow the cuts incrementally, the report is written.
#include <gtest/gtest.h>

#include <fstream>
#include <sstream>

#include "app/headless.h"
#include "app_test_util.h"
#include "cutting/validate.h"
#include "engine/mesh_check.h"
#include "engine/mesh_io.h"

namespace serosa::app {
namespace {

using namespace serosa::app::testing;

// The tets of `group` as a mesh of their own (all nodes kept; unused ones are not counted).
TetMesh group_only(const TetMesh& m, std::uint16_t group) {
  TetMesh g;
  g.rest = m.rest;
  g.fill_node_state();
  for (std::int32_t t = 0; t < m.num_tets(); ++t)
    if (m.group[static_cast<std::size_t>(t)] == group)
      g.add_tet(m.tets[static_cast<std::size_t>(t)], group);
  return g;
}

TEST(Transection, ScissorsCutTheAppendixInTwo) {
  const fs::path dir = out_dir("transection");
  HeadlessOptions o;
  o.scene = source("config/appendectomy.toml");
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

  // The appendix (group 1) is in two pieces; before the cut it was one.
  const TetMesh before = read_mesh(source("assets/appendectomy_coarse.msh"));
  EXPECT_EQ(cutting::count_components(group_only(before, 1)), 1);
  const TetMesh after = read_mesh(dir / "final.msh");
  EXPECT_EQ(cutting::count_components(group_only(after, 1)), 2);
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
    std::ifstream in(source("config/appendectomy.toml"));
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

}  // namespace
}  // namespace serosa::app
