// Effects: app builds a stage only for what the scene lists (docs/ARCHITECTURE.md "Effects").
#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <map>
#include <string>
#include <vector>

#include "app/assemble_state.h"
#include "app/compose.h"
#include "app/render_frame_from_surface.h"
#include "engine/io/mesh_io.h"
#include "engine/scene/scene.h"
#include "engine/sim_state.h"
#include "support/test_paths.h"

namespace serosa::app {
namespace {

namespace fs = std::filesystem;

const fs::path kBeam = fs::path(::serosa::test_paths::source_dir()) / "assets" / "beam_xcoarse.msh";

Scene scene_with(const std::string& effects, const std::string& extra = {}) {
  const fs::path scene_path =
      fs::path(::serosa::test_paths::source_dir()) / "assets" / "test_scene.toml";
  const std::string toml = "[scene]\ndt = 0.01\neffects = [" + effects +
                           "]\n[[organ]]\nname = \"beam\"\nmesh = \"beam_xcoarse.msh\"\n"
                           "fixed = { box = [[-0.001, -1, -1], [0.001, 1, 1]] }\n" +
                           extra;
  return parse_scene_text(toml, scene_path);
}

TEST(Compose, NoEffectsBuildsNoStage) {
  const Scene scene = scene_with("");
  const AssembledScene a = assemble_state(scene);
  const Composition c = compose(scene, a);
  EXPECT_EQ(c.runner->num_stages(), 0u);
  EXPECT_EQ(c.fem, nullptr);
  EXPECT_EQ(c.tools, nullptr);
  EXPECT_TRUE(c.built.empty());
}

// Every solver key the scene reads reaches the FEM's settings: a key that stopped on the way
// would be a knob that does nothing.
TEST(Compose, TheScenesSolverKeysReachTheFem) {
  Scene scene = scene_with("");
  SolverSettings& s = scene.solver;
  s.kind = SolverKind::kPcgLagged;
  s.threads = 2;
  s.tolerance = 3e-4;
  s.max_iterations = 77;
  s.refresh_iterations = 5;
  s.factor_lag_steps = 9;
  s.urgent_lag_steps = 4;
  s.cut_lag_steps = 31;
  s.misfit_rad = 0.35;
  s.patch_rings = 3;
  s.patch_after_cut = false;
  const fem::FemConfig c = fem_config(scene, assemble_state(scene));
  EXPECT_EQ(c.solver.kind, fem::SolverKind::pcg_lagged);
  EXPECT_EQ(c.solver.threads, 2);
  EXPECT_DOUBLE_EQ(c.solver.tolerance, 3e-4);
  EXPECT_EQ(c.solver.max_iterations, 77);
  EXPECT_EQ(c.solver.refresh_iterations, 5);
  EXPECT_EQ(c.solver.factor_lag_steps, 9);
  EXPECT_EQ(c.solver.urgent_lag_steps, 4);
  EXPECT_EQ(c.solver.cut_lag_steps, 31);
  EXPECT_DOUBLE_EQ(c.solver.misfit_rad, 0.35);
  EXPECT_EQ(c.solver.patch_rings, 3);
  EXPECT_FALSE(c.solver.patch_after_cut);
}

TEST(Compose, OnlyListedEffectsAreBuilt) {
  const Scene scene = scene_with("\"fem\"");
  const AssembledScene a = assemble_state(scene);
  const Composition c = compose(scene, a);
  ASSERT_NE(c.fem, nullptr);
  // FEM alone: no tool, so no metrics either (they score tools and cuts).
  ASSERT_EQ(c.runner->num_stages(), 1u);
  EXPECT_EQ(c.runner->timings()[0].name, "fem");
  EXPECT_EQ(c.cutting, nullptr);
  EXPECT_EQ(c.surface, nullptr);
  EXPECT_EQ(c.contact, nullptr);
  ASSERT_EQ(c.built.size(), 1u);
  EXPECT_EQ(c.built[0], Effect::kFem);
  EXPECT_TRUE(c.folded.empty());
}

TEST(Compose, UnlistedStagesTakeNoTimeInAStep) {
  // Without "fem", stepping a scene leaves positions untouched and runs no stage at all.
  const Scene scene = scene_with("");
  AssembledScene a = assemble_state(scene);
  Composition c = compose(scene, a);
  const auto before = a.state.mesh.x;
  c.runner->run(a.state, 10);
  EXPECT_EQ(a.state.mesh.x, before);
  EXPECT_TRUE(c.runner->timings().empty());
  EXPECT_EQ(a.state.step, 10u);
}

TEST(Compose, ListedButUnimplementedEffectsAreReportedNotFaked) {
  const Scene scene = scene_with("\"fem\", \"surface\", \"record\"");
  const AssembledScene a = assemble_state(scene);
  const Composition c = compose(scene, a);
  for (Effect e : c.unavailable) {
    EXPECT_TRUE(scene.settings.has(e));
    EXPECT_EQ(std::count(c.built.begin(), c.built.end(), e), 0);
  }
  EXPECT_EQ(c.built.size() + c.folded.size() + c.unavailable.size(), scene.settings.effects.size());
}

// The default scene lists "bleeding" and "smoke": their stages run after the metrics that find
// the cut artery and after the cutting stage whose hooks coagulate; without them listed there are
// no such stages, and nothing publishes blood or smoke.
TEST(Compose, BleedingAndSmokeAreBuiltOnlyWhenListed) {
  Scene scene =
      load_scene(fs::path(::serosa::test_paths::source_dir()) / "config" / "appendectomy.toml");
  ASSERT_TRUE(scene.settings.has(Effect::kBleeding));
  ASSERT_TRUE(scene.settings.has(Effect::kSmoke));
  const auto stage_names = [](const Composition& c) {
    std::vector<std::string> names;
    for (const auto& t : c.runner->timings()) names.push_back(t.name);
    return names;
  };
  {
    const AssembledScene a = assemble_state(scene);
    const Composition c = compose(scene, a);
    const auto names = stage_names(c);
    ASSERT_EQ(std::count(names.begin(), names.end(), "bleeding"), 1);
    EXPECT_EQ(names.back(), "bleeding");
    EXPECT_EQ(std::count(c.built.begin(), c.built.end(), Effect::kBleeding), 1);
    const auto smoke = std::find(names.begin(), names.end(), "smoke");
    ASSERT_NE(smoke, names.end());
    EXPECT_EQ(*(smoke - 1), "cutting");
  }
  scene.settings.effects.erase(Effect::kBleeding);
  scene.settings.effects.erase(Effect::kSmoke);
  AssembledScene a = assemble_state(scene);
  Composition c = compose(scene, a);
  const auto names = stage_names(c);
  EXPECT_EQ(std::count(names.begin(), names.end(), "bleeding"), 0);
  EXPECT_EQ(std::count(names.begin(), names.end(), "smoke"), 0);
  EXPECT_EQ(std::count(c.built.begin(), c.built.end(), Effect::kBleeding), 0);
  // A bleeding the metrics found is not drawn as blood then: nothing is published or allocated.
  a.state.shared.bleeds.emplace_back(Vec3::Zero(), 0.0);
  c.runner->run(a.state, 2);
  EXPECT_EQ(a.state.shared.blood.capacity(), 0u);
  EXPECT_EQ(a.state.blocks.bleeding.stain.capacity(), 0u);
  a.state.blocks.cutting.coagulated.assign(a.state.mesh.x.size(), 1);
  c.runner->run(a.state, 2);
  EXPECT_EQ(a.state.shared.smoke.capacity(), 0u);
}

// [render] looks: a group is drawn as the tissue the scene names for it, the others by their own
// names.
TEST(Compose, LooksNameTheTissueAGroupIsDrawnAs) {
  Scene scene;
  scene.render.looks = {{"appendix", "fat"}};
  const std::map<int, std::string> drawn =
      drawn_group_names(scene, {{1, "appendix"}, {2, "cecum"}});
  EXPECT_EQ(drawn, (std::map<int, std::string>{{1, "fat"}, {2, "cecum"}}));
}

TEST(Compose, GravityPullsTheFreeEndDown) {
  const Scene scene = scene_with("\"fem\", \"gravity\"");
  AssembledScene a = assemble_state(scene);
  Composition c = compose(scene, a);
  std::int32_t tip = 0;
  for (std::int32_t i = 0; i < a.state.mesh.num_nodes(); ++i)
    if (a.state.mesh.rest[i].x() > a.state.mesh.rest[tip].x()) tip = i;
  const double y0 = a.state.mesh.x[tip].y();
  c.runner->run(a.state, 20);
  EXPECT_LT(a.state.mesh.x[tip].y(), y0);
  for (std::int32_t i = 0; i < a.state.mesh.num_nodes(); ++i)
    if (a.state.mesh.fixed[i]) {
      EXPECT_EQ(a.state.mesh.x[i], a.state.mesh.rest[i]);
    }
}

TEST(AssembleState, FixedBoxAndGroupsApply) {
  const Scene scene = scene_with("\"fem\"");
  const AssembledScene a = assemble_state(scene);
  int fixed = 0;
  for (std::int32_t i = 0; i < a.state.mesh.num_nodes(); ++i) {
    const bool at_wall = std::abs(a.state.mesh.rest[i].x()) <= 0.001;
    EXPECT_EQ(a.state.mesh.fixed[i] != 0, at_wall) << "node " << i;
    fixed += at_wall;
  }
  EXPECT_GT(fixed, 0);
  ASSERT_EQ(a.groups.size(), 1u);
  EXPECT_EQ(a.groups.begin()->second.name, "beam");
}

}  // namespace
}  // namespace serosa::app
