// fem/fem_stage.h: the stage steps SimState::mesh through the engine's Runner.
#include "fem/fem_stage.h"

#include <gtest/gtest.h>

#include <memory>

#include "engine/runner.h"
#include "engine/sim_state.h"
#include "fem_fixtures.h"

namespace serosa::fem {
namespace {

TEST(FemStage, StepsTheMeshUnderGravityThroughTheRunner) {
  SimState s;
  s.mesh = test_meshes::kuhn_bar(8, 2, 2, 0.01, 0.01, 0.01);
  for (std::size_t i = 0; i < s.mesh.rest.size(); ++i) s.mesh.fixed[i] = s.mesh.rest[i].x() < 1e-12;
  FemConfig cfg;
  cfg.default_material = FemMaterial{1e5, 0.45, 1000.0, 0.5, 0.01};
  auto stage = std::make_unique<FemStage>(cfg);
  FemStage* fem = stage.get();
  EXPECT_EQ(fem->name(), "fem");
  Runner runner(0.01);
  runner.add(Slot::fem, std::move(stage));
  runner.run(s, 20);
  EXPECT_EQ(fem->stats().steps, 20u);
  EXPECT_EQ(fem->stats().rebuilds, 1u);
  EXPECT_EQ(fem->stats().rejected, 0u);
  EXPECT_TRUE(fem->last_status().applied);
  double total_mass = 0.0;
  for (double m : s.mesh.mass) total_mass += m;
  EXPECT_NEAR(total_mass, 1000.0 * 0.08 * 0.02 * 0.02, 1e-12);
  // The free end sags, the clamped end stays.
  const std::size_t tip = 8;  // node (8, 0, 0)
  EXPECT_LT(s.mesh.x[tip].y(), s.mesh.rest[tip].y());
  EXPECT_EQ(s.mesh.x[0], s.mesh.rest[0]);
}

TEST(FemStage, ExternalForcesAndGravityOff) {
  SimState s;
  s.mesh = test_meshes::kuhn_bar(4, 1, 1, 0.01, 0.01, 0.01);
  for (std::size_t i = 0; i < s.mesh.rest.size(); ++i) s.mesh.fixed[i] = s.mesh.rest[i].x() < 1e-12;
  FemConfig cfg;
  cfg.gravity_on = false;
  FemStage fem(cfg);
  const StepContext ctx{0, 0.0, 0.01};
  for (int k = 0; k < 5; ++k) fem.step(ctx, s);  // no gravity, no force: nothing moves
  for (std::size_t i = 0; i < s.mesh.x.size(); ++i)
    EXPECT_LE((s.mesh.x[i] - s.mesh.rest[i]).norm(), 1e-15);  // round-off of F = I only
  // Push the tip node up along z, as the contact stage hands forces over.
  s.events.external_force_n.assign(s.mesh.rest.size(), Vec3::Zero());
  s.events.external_force_n[4].z() = 1e-3;
  for (int k = 0; k < 5; ++k) fem.step(ctx, s);
  EXPECT_GT(s.mesh.x[4].z(), s.mesh.rest[4].z() + 1e-4);
  EXPECT_TRUE(fem.last_status().applied);
}

}  // namespace
}  // namespace serosa::fem
