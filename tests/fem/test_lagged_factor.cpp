// pcg_lagged: CG preconditioned by a CHOLMOD factor of a recent step's own system matrix. The
// refresh schedule depends only on the step count and the iteration counts, so a run that factors
// in a background thread gives the same bits as one that factors in place; the result stays
// within the CG tolerance of the direct solver through large rotations, a newly held node and a
// topology change (patched, or factored at once); and a fresh factor brings CG back to a few
// iterations.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <numbers>
#include <tuple>
#include <vector>

#include "engine/topology_delta.h"
#include "fem/implicit_integrator.h"
#include "fem_fixtures.h"

namespace serosa::fem {
namespace {

TetMesh bar() { return fixtures::clamped_bar(8, 2, 2, 0.05, 0.05, 0.05); }

FemConfig config(SolverKind kind, bool background, bool patch = true, bool matrix_free = false) {
  FemConfig c;
  c.solver.matrix_free = matrix_free;
  c.solver.patch_after_cut = patch;
  c.default_material = FemMaterial{5e4, 0.4, 1000.0, 0.1, 0.01};
  c.solver.kind = kind;
  c.solver.tolerance = 1e-8;
  c.solver.max_iterations = 2000;
  c.solver.background_factor = background;
  c.gravity_on = true;
  return c;
}

// The free end of the bar, the node farthest from x = 0.
std::size_t tip(const TetMesh& m) {
  std::size_t best = 0;
  for (std::size_t i = 0; i < m.rest.size(); ++i)
    if (m.rest[i].x() > m.rest[best].x()) best = i;
  return best;
}

struct History {
  TetMesh mesh;
  std::vector<StepStatus> steps;
};

// 120 steps of 10 ms: the bar swings down under gravity (large rotations), its tip is grabbed
// (held fixed) at step 40 and let go at step 80, and a tet is split at step 60.
History run(SolverKind kind, bool background, bool patch = true, bool matrix_free = false) {
  History r{bar(), {}};
  ImplicitIntegrator integ(config(kind, background, patch, matrix_free));
  const std::size_t held = tip(r.mesh);
  for (int k = 0; k < 120; ++k) {
    // Holding or letting go is the caller's doing, not an energy gain of the solve.
    if (k == 40 || k == 80) {
      r.mesh.fixed[held] = k == 40 ? 1 : 0;
      integ.restart_energy_balance();
    }
    if (k == 60) {
      TopologyDelta d = fixtures::split_tet(r.mesh, 7);
      apply(r.mesh, d);
      integ.update(r.mesh, d);
    }
    r.steps.push_back(integ.step(r.mesh, 0.01));
  }
  return r;
}

TEST(LaggedFactor, BackgroundAndInPlaceFactoringGiveTheSameBits) {
  const History a = run(SolverKind::pcg_lagged, true);
  const History b = run(SolverKind::pcg_lagged, false);
  ASSERT_EQ(a.mesh.x.size(), b.mesh.x.size());
  for (std::size_t i = 0; i < a.mesh.x.size(); ++i) {
    ASSERT_EQ(a.mesh.x[i], b.mesh.x[i]) << "node " << i;
    ASSERT_EQ(a.mesh.v[i], b.mesh.v[i]) << "node " << i;
  }
  for (std::size_t k = 0; k < a.steps.size(); ++k) {
    ASSERT_EQ(a.steps[k].iterations, b.steps[k].iterations) << "step " << k;
    // Only a background thread is waited for: in place, no step ever waits. (How long the
    // background run waited is the machine's, and changes no bit: the positions above.)
    EXPECT_EQ(b.steps[k].factor_wait_ms, 0.0) << "step " << k;
  }
}

TEST(LaggedFactor, StaysWithinTheToleranceOfTheDirectSolver) {
  const History lagged = run(SolverKind::pcg_lagged, true);
  const History direct = run(SolverKind::cholmod, false);
  double max_disp = 0.0;
  double max_diff = 0.0;
  for (std::size_t i = 0; i < direct.mesh.x.size(); ++i) {
    max_disp = std::max(max_disp, (direct.mesh.x[i] - direct.mesh.rest[i]).norm());
    max_diff = std::max(max_diff, (lagged.mesh.x[i] - direct.mesh.x[i]).norm());
  }
  EXPECT_GT(max_disp, 0.05);  // it did swing: rotations the rest state does not know
  EXPECT_LT(max_diff, 1e-5 * max_disp);
  for (std::size_t k = 0; k < lagged.steps.size(); ++k) {
    EXPECT_TRUE(lagged.steps[k].applied) << "step " << k;
    // Grabbing the swinging tip is itself flagged as a gain by the divergence guard, for either
    // solver; every other step converges.
    if (!direct.steps[k].energy_gain) {
      EXPECT_TRUE(lagged.steps[k].converged) << "step " << k;
    }
  }
}

TEST(LaggedFactor, RefreshesKeepCgToAFewIterations) {
  const History r = run(SolverKind::pcg_lagged, false);
  int refreshes = 0;
  for (const StepStatus& s : r.steps) refreshes += s.factor_refresh ? 1 : 0;
  EXPECT_GE(refreshes, 3);  // the first step, the cut, and the swing
  // The cut's step patches the old factor with one of the rows the cut touched; a refresh of the
  // new structure is asked for as soon as no other is pending, and CG needs a few more
  // iterations until it is installed.
  EXPECT_TRUE(r.steps[60].factor_patch);
  bool refreshed = false;
  for (int k = 60; k < 80; ++k)
    refreshed = refreshed || r.steps[static_cast<std::size_t>(k)].factor_refresh;
  EXPECT_TRUE(refreshed);
  EXPECT_LE(r.steps[60].iterations, 4 * std::max(r.steps[59].iterations, 3));
  // Without the patch the cut's step factors the new structure at once: it converges like any
  // other.
  const History now = run(SolverKind::pcg_lagged, false, /*patch=*/false);
  EXPECT_FALSE(now.steps[60].factor_patch);
  EXPECT_TRUE(now.steps[60].factor_refresh);
  EXPECT_LE(now.steps[60].iterations, 3);
  // With the tolerance at 1e-8 a step needs a handful of iterations: far fewer than Jacobi's.
  int sum = 0;
  for (const StepStatus& s : r.steps) sum += s.iterations;
  const History jacobi = run(SolverKind::pcg, false);
  int jacobi_sum = 0;
  for (const StepStatus& s : jacobi.steps) jacobi_sum += s.iterations;
  EXPECT_LT(sum * 5, jacobi_sum);
  EXPECT_LT(static_cast<double>(sum) / static_cast<double>(r.steps.size()), 12.0);
  // Holding the swinging tip changes A in its rows; the filtered, turned factor absorbs it.
  EXPECT_LE(r.steps[40].iterations, 3 * r.steps[39].iterations);
}

}  // namespace
}  // namespace serosa::fem

namespace serosa::fem {
namespace {

// prepare() does at load time what the first step would do (the structure, the first factor):
// the run is the same, bit for bit, with or without it.
TEST(LaggedFactor, PrepareGivesTheSameBitsAsTheFirstStep) {
  for (int variant = 0; variant < 4; ++variant) {
    const bool plastic = (variant & 1) != 0;
    TetMesh a = bar(), b = bar();
    FemConfig c = config(SolverKind::pcg_lagged, false, true, /*matrix_free=*/variant >= 2);
    c.plasticity = {true, 1e-3, 10.0, 0.1};
    if (!plastic) c.plasticity = {};
    ImplicitIntegrator ia(c), ib(c);
    ia.prepare(a, 0.01);
    for (int k = 0; k < 30; ++k) {
      const StepStatus sa = ia.step(a, 0.01);
      const StepStatus sb = ib.step(b, 0.01);
      ASSERT_EQ(sa.iterations, sb.iterations) << "step " << k;
      if (k == 0) {
        EXPECT_FALSE(sa.factor_refresh);  // prepared: nothing to factor
        EXPECT_TRUE(sb.factor_refresh);
      }
    }
    for (std::size_t i = 0; i < a.x.size(); ++i) {
      ASSERT_EQ(a.x[i], b.x[i]) << "node " << i;
      ASSERT_EQ(a.v[i], b.v[i]) << "node " << i;
    }
  }
}

}  // namespace
}  // namespace serosa::fem

namespace serosa::fem {
namespace {

// A grasp holds a patch of nodes on the swinging bar's top face at step 30 and lets go at step 60.
// The factor of the steps before knew those nodes as free; patching their rows and their ring
// keeps CG near its usual iterations through both changes, where masking the held rows alone
// (block Jacobi across the grasp) needed 68 a step after the release until a refresh came.
struct GraspRun {
  std::vector<StepStatus> steps;
  TetMesh mesh;
};

GraspRun grasp_run(SolverKind kind, bool matrix_free = false, double tolerance = 1e-6,
                   double misfit_rad = SolverSettings{}.misfit_rad) {
  GraspRun r{{}, fixtures::clamped_bar(12, 3, 3, 0.02, 0.02, 0.02)};
  FemConfig c = config(kind, false, true, matrix_free);
  c.solver.tolerance = tolerance;
  c.solver.misfit_rad = misfit_rad;
  c.solver.max_iterations = 5000;
  ImplicitIntegrator integ(c);
  std::vector<std::size_t> held;  // the top face's nodes two thirds along the bar
  for (std::size_t i = 0; i < r.mesh.rest.size(); ++i) {
    const Vec3& p = r.mesh.rest[i];
    if (p.z() > 0.059 && p.x() > 0.14 && p.x() < 0.19) held.push_back(i);
  }
  for (int k = 0; k < 90; ++k) {
    if (k == 30 || k == 60) {
      for (const std::size_t i : held) r.mesh.fixed[i] = k == 30 ? 1 : 0;
      integ.restart_energy_balance();
    }
    r.steps.push_back(integ.step(r.mesh, 0.01));
  }
  return r;
}

// The step that patches (a grasp, a release, a cut) fills only the patch's rows; the refresh,
// which takes the whole matrix, is asked for on the step after it.
TEST(LaggedFactor, TheStepThatPatchesLeavesTheRefreshToTheNext) {
  const GraspRun g = grasp_run(SolverKind::pcg_lagged);
  for (const int k : {30, 60}) {
    EXPECT_TRUE(g.steps[static_cast<std::size_t>(k)].factor_patch) << "step " << k;
    EXPECT_FALSE(g.steps[static_cast<std::size_t>(k)].factor_refresh) << "step " << k;
    EXPECT_TRUE(g.steps[static_cast<std::size_t>(k + 1)].factor_refresh) << "step " << k + 1;
  }
  const History c = run(SolverKind::pcg_lagged, false);
  EXPECT_TRUE(c.steps[60].factor_patch);
  EXPECT_FALSE(c.steps[60].factor_refresh);
}

TEST(LaggedFactor, AGraspAndItsReleaseArePatchedAndCostCgLittle) {
  const GraspRun r = grasp_run(SolverKind::pcg_lagged);
  const auto it = [&](int k) { return r.steps[static_cast<std::size_t>(k)].iterations; };
  EXPECT_TRUE(r.steps[30].factor_patch);
  EXPECT_TRUE(r.steps[60].factor_patch);
  // The swing alone patches misfit nodes (fem/lagged_factor.h); without those, only the grasp's
  // and the release's steps patch.
  const GraspRun only = grasp_run(SolverKind::pcg_lagged, false, 1e-6, /*misfit_rad=*/0.0);
  for (int k = 1; k < 90; ++k) {
    EXPECT_EQ(only.steps[static_cast<std::size_t>(k)].factor_patch, k == 30 || k == 60)
        << "step " << k;
  }
  int usual = 0;  // the most a step of the free swing needed
  for (int k = 10; k < 30; ++k) usual = std::max(usual, it(k));
  for (int k = 30; k < 90; ++k) EXPECT_LE(it(k), 2 * usual) << "step " << k;
  // Within the tolerance of a converged solve all along (Jacobi CG: CHOLMOD's direct solver runs
  // OpenMP threads of its own on this size, which ThreadSanitizer cannot follow).
  const GraspRun direct = grasp_run(SolverKind::pcg, false, 1e-11);
  double max_disp = 0.0, max_diff = 0.0;
  for (std::size_t i = 0; i < direct.mesh.x.size(); ++i) {
    max_disp = std::max(max_disp, (direct.mesh.x[i] - direct.mesh.rest[i]).norm());
    max_diff = std::max(max_diff, (r.mesh.x[i] - direct.mesh.x[i]).norm());
  }
  EXPECT_GT(max_disp, 0.01);
  EXPECT_LT(max_diff, 1e-3 * max_disp);
}

}  // namespace
}  // namespace serosa::fem

namespace serosa::fem {
namespace {

// Matrix-free, pcg_lagged applies A per tet and fills the blocks only on the steps that factor or
// patch: the same matrix, so the same iterations, refreshes and patches as the assembled product,
// and the same positions to far inside the tolerance (only the products' rounding differs).
TEST(LaggedFactor, MatrixFreeProductBehavesAsTheAssembledOne) {
  const History a = run(SolverKind::pcg_lagged, false);
  const History f = run(SolverKind::pcg_lagged, false, true, /*matrix_free=*/true);
  const GraspRun ga = grasp_run(SolverKind::pcg_lagged);
  const GraspRun gf = grasp_run(SolverKind::pcg_lagged, /*matrix_free=*/true);
  for (const auto& [x, y, steps_x, steps_y] :
       {std::tuple{&a.mesh, &f.mesh, &a.steps, &f.steps},
        std::tuple{&ga.mesh, &gf.mesh, &ga.steps, &gf.steps}}) {
    double max_disp = 0.0, max_diff = 0.0;
    for (std::size_t i = 0; i < x->x.size(); ++i) {
      max_disp = std::max(max_disp, (x->x[i] - x->rest[i]).norm());
      max_diff = std::max(max_diff, (x->x[i] - y->x[i]).norm());
    }
    EXPECT_GT(max_disp, 0.01);
    EXPECT_LT(max_diff, 1e-6 * max_disp);
    int refreshes = 0, patches = 0;
    for (std::size_t k = 0; k < steps_x->size(); ++k) {
      const StepStatus& sx = (*steps_x)[k];
      const StepStatus& sy = (*steps_y)[k];
      EXPECT_NEAR(sx.iterations, sy.iterations, 1) << "step " << k;
      EXPECT_EQ(sx.factor_patch, sy.factor_patch) << "step " << k;
      EXPECT_TRUE(sy.converged || sy.energy_gain) << "step " << k;
      refreshes += sy.factor_refresh ? 1 : 0;
      patches += sy.factor_patch ? 1 : 0;
    }
    EXPECT_GE(refreshes, 3);
    EXPECT_GE(patches, 1);
  }
}

}  // namespace
}  // namespace serosa::fem
