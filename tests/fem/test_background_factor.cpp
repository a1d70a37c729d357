// pcg_cholmod: the rest-state CHOLMOD factor is computed in a background
// thread; a step after a topology change does not wait for it (it runs CG with Jacobi and says
// so in its status) and converges; once the factor is ready CG uses it and needs fewer
// iterations; results match the direct solver.
#include <gtest/gtest.h>

#include <vector>

#include "engine/topology_delta.h"
#include "fem/implicit_integrator.h"
#include "fem_fixtures.h"

namespace serosa::fem {
namespace {

TetMesh bar() { return fixtures::clamped_bar(8, 2, 2, 0.05, 0.05, 0.05); }

FemConfig config(int delay_ms) {
  FemConfig c;
  c.default_material = FemMaterial{5e4, 0.4, 1000.0, 0.1, 0.01};
  c.solver.kind = SolverKind::pcg_cholmod;
  c.solver.tolerance = 1e-9;
  c.solver.max_iterations = 2000;
  c.solver.factor_delay_ms = delay_ms;
  return c;
}

TEST(BackgroundFactor, StepAfterTopologyChangeDoesNotWaitAndConverges) {
  // The factorization starts 400 ms late: a step (a few ms here) that waited for it could not
  // report factor_pending.
  TetMesh m = bar();
  ImplicitIntegrator integ(config(400));
  const StepStatus first = integ.step(m, 0.01);
  EXPECT_TRUE(first.factor_pending);
  EXPECT_TRUE(first.converged);
  EXPECT_TRUE(first.applied);
  integ.wait_for_background();
  const StepStatus with_factor = integ.step(m, 0.01);
  EXPECT_FALSE(with_factor.factor_pending);
  EXPECT_TRUE(with_factor.converged);

  TopologyDelta d = fixtures::split_tet(m, 5);
  apply(m, d);
  integ.update(m, d);
  const StepStatus after_cut = integ.step(m, 0.01);
  EXPECT_TRUE(after_cut.factor_pending);  // the old factor has the old size: Jacobi
  EXPECT_TRUE(after_cut.converged);
  EXPECT_TRUE(after_cut.applied);
  const StepStatus jacobi_again = integ.step(m, 0.01);
  integ.wait_for_background();
  const StepStatus factored = integ.step(m, 0.01);
  EXPECT_FALSE(factored.factor_pending);
  EXPECT_TRUE(factored.converged);
  EXPECT_LT(factored.iterations, jacobi_again.iterations);
  for (std::size_t i = 0; i < m.x.size(); ++i) ASSERT_TRUE(m.x[i].allFinite());
}

TEST(BackgroundFactor, SameTrajectoryAsTheDirectSolver) {
  TetMesh a = bar();
  TetMesh b = bar();
  FemConfig direct = config(0);
  direct.solver.kind = SolverKind::cholmod;
  direct.solver.tolerance = 1e-12;
  ImplicitIntegrator ia(config(0));
  ImplicitIntegrator ib(direct);
  int pending = 0;
  for (int s = 0; s < 30; ++s) {
    const StepStatus sa = ia.step(a, 0.01);
    ASSERT_TRUE(sa.converged);
    pending += sa.factor_pending ? 1 : 0;
    ASSERT_TRUE(ib.step(b, 0.01).applied);
  }
  double diff = 0.0, disp = 0.0;
  for (std::size_t i = 0; i < a.x.size(); ++i) {
    diff = std::max(diff, (a.x[i] - b.x[i]).norm());
    disp = std::max(disp, (b.x[i] - b.rest[i]).norm());
  }
  EXPECT_GT(disp, 0.0);
  EXPECT_LE(diff, 1e-5 * disp);
  EXPECT_LE(pending, 30);
}

TEST(BackgroundFactor, SynchronousModeFactorsOnTheStep) {
  TetMesh m = bar();
  FemConfig c = config(0);
  c.solver.background_factor = false;
  ImplicitIntegrator integ(c);
  const StepStatus st = integ.step(m, 0.01);
  EXPECT_FALSE(st.factor_pending);
  EXPECT_TRUE(st.converged);
}

}  // namespace
}  // namespace serosa::fem
