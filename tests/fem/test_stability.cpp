// Stability on hard cases: slivers down to quality ~1e-6 from near-degenerate
// splits, time steps from 1e-4 to 0.05 s, and a 1e6 stiffness contrast, for each solver: every
// step is applied or clearly rejected, no NaN, and the energy stays bounded.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <vector>

#include "engine/mesh_quality.h"
#include "engine/topology_delta.h"
#include "fem/implicit_integrator.h"
#include "fem_fixtures.h"

namespace serosa::fem {
namespace {

TetMesh soft_bar() { return fixtures::clamped_bar(6, 2, 2, 0.05, 0.05, 0.05); }

FemConfig soft(SolverKind kind) {
  FemConfig c;
  c.default_material = FemMaterial{3000.0, 0.45, 1000.0, 0.1, 0.1};
  c.solver.kind = kind;
  c.solver.tolerance = 1e-6;
  c.solver.max_iterations = 200;
  return c;
}

// The soft bar's tets alternating between 3 kPa (group 1) and `stiff_pa` (group 2), Rayleigh
// damping `damping` on both, solved by CG capped at `iterations` with a tolerance it cannot reach.
FemConfig alternating_stiffness(TetMesh& m, double stiff_pa, double damping, int iterations,
                                double tolerance) {
  for (std::size_t t = 0; t < m.tets.size(); ++t) m.group[t] = t % 2 == 0 ? 1 : 2;
  FemConfig c = soft(SolverKind::pcg);
  c.materials[1] = FemMaterial{3000.0, 0.45, 1000.0, damping, damping};
  c.materials[2] = FemMaterial{stiff_pa, 0.45, 1000.0, damping, damping};
  c.solver.max_iterations = iterations;
  c.solver.tolerance = tolerance;
  return c;
}

// Kinetic energy plus gravitational potential relative to rest (J). Starting at rest, a
// dissipative step keeps kinetic + gravitational + elastic energy <= 0, so this is <= 0 (elastic
// energy >= 0); and the bar, clamped at x = 0 and 0.3 m long, cannot fall further than its
// length: >= -M g L.
void expect_bounded(const TetMesh& m, double e) {
  double total = 0.0;
  for (double mi : m.mass) total += mi;
  EXPECT_LE(e, 1e-9 * total);
  EXPECT_GE(e, -total * 9.81 * 0.3);
}

double energy(const TetMesh& m) {
  double e = 0.0;
  for (std::size_t i = 0; i < m.x.size(); ++i)
    e += 0.5 * m.mass[i] * m.v[i].squaredNorm() + m.mass[i] * 9.81 * (m.x[i].y() - m.rest[i].y());
  return e;
}

TEST(Stability, SliversFromNearDegenerateSplits) {
  for (SolverKind kind : {SolverKind::pcg, SolverKind::cholmod, SolverKind::pcg_cholmod}) {
    TetMesh m = soft_bar();
    ImplicitIntegrator integ(soft(kind));
    ASSERT_TRUE(integ.step(m, 0.01).applied);
    for (std::int32_t t : {3, 40, 90, 130}) {
      const double tiny = 1e-6;
      TopologyDelta d = fixtures::split_tet(m, t, {0.3, 0.3, 0.4 - tiny, tiny});
      apply(m, d);
      integ.update(m, d);
    }
    double worst = 1.0;
    for (std::int32_t t = 0; t < m.num_tets(); ++t)
      worst = std::min(worst, std::abs(m.rest_volume(t)));
    EXPECT_LT(worst, 1e-9);  // slivers really are there (volume ~1e-6 of a 2e-5 m^3 tet)
    for (int s = 0; s < 100; ++s) {
      const StepStatus st = integ.step(m, 0.01);
      ASSERT_TRUE(st.applied || !st.converged);
    }
    for (std::size_t i = 0; i < m.x.size(); ++i) {
      ASSERT_TRUE(m.x[i].allFinite());
      ASSERT_TRUE(m.v[i].allFinite());
    }
    SCOPED_TRACE(static_cast<int>(kind));
    expect_bounded(m, energy(m));
  }
}

TEST(Stability, TimeStepsFrom1e4To005) {
  for (double dt : {1e-4, 1e-3, 1e-2, 5e-2}) {
    for (SolverKind kind : {SolverKind::pcg, SolverKind::cholmod}) {
      TetMesh m = soft_bar();
      ImplicitIntegrator integ(soft(kind));
      const int steps = std::max(20, static_cast<int>(0.5 / dt / 25.0));
      SCOPED_TRACE(dt);
      for (int s = 0; s < steps; ++s) {
        const StepStatus st = integ.step(m, dt);
        EXPECT_TRUE(st.applied);
        expect_bounded(m, energy(m));
      }
      for (std::size_t i = 0; i < m.x.size(); ++i) ASSERT_TRUE(m.x[i].allFinite());
    }
  }
}

TEST(Stability, UnconvergedSolveIsReportedNotHidden) {
  // A 1e6 stiffness contrast with a 3-iteration cap cannot converge: the status says so, and the
  // (finite, energy-reducing) result is still applied.
  TetMesh m = soft_bar();
  const FemConfig c = alternating_stiffness(m, 3e9, 0.1, 3, 1e-10);
  ImplicitIntegrator integ(c);
  for (int s = 0; s < 20; ++s) {
    const StepStatus st = integ.step(m, 0.01);
    EXPECT_FALSE(st.converged);
    EXPECT_EQ(st.iterations, 3);
    EXPECT_GT(st.residual, 1e-10);
  }
  for (std::size_t i = 0; i < m.x.size(); ++i) ASSERT_TRUE(m.x[i].allFinite());
}

// Divergence guard (StepStatus::energy_gain): a converged run under gravity (the energy balance
// holds step after step: never flagged, and the balance is a loss or within round-off) against
// energy injected between steps (nodes kicked by the caller, as a solve that diverges slowly
// would do it): the next step flags it, reports converged = false, and the run goes on.
TEST(DivergenceGuard, ConvergedStepsNeverFlagAndAnEnergyGainIsFlagged) {
  for (const SolverKind kind : {SolverKind::pcg, SolverKind::cholmod}) {
    SCOPED_TRACE(kind == SolverKind::pcg ? "pcg" : "cholmod");
    TetMesh m = soft_bar();
    FemConfig c = soft(kind);
    c.solver.tolerance = 1e-10;
    c.solver.max_iterations = 2000;
    ImplicitIntegrator integ(c);
    double total = 0.0;
    for (int s = 0; s < 300; ++s) {
      const StepStatus st = integ.step(m, 0.01);
      ASSERT_TRUE(st.applied);
      EXPECT_FALSE(st.energy_gain)
          << "step " << s << ": " << st.energy_change_j << " J of " << st.energy_j;
      EXPECT_TRUE(st.converged) << "step " << s;
      EXPECT_LE(st.energy_change_j, 1e-6 * st.energy_j + 1e-15) << "step " << s;
      total += st.energy_change_j;
    }
    EXPECT_LT(total, 0.0);  // damping dissipated energy on balance
    // Kick: 0.1 m/s on every free node adds kinetic energy no force paid for (~0.015 J, against
    // ~3e-4 J dissipated per step).
    StepStatus st = integ.step(m, 0.01);
    ASSERT_FALSE(st.energy_gain);
    for (std::size_t i = 0; i < m.v.size(); ++i)
      if (m.fixed[i] == 0) m.v[i] += Vec3(0.0, 0.0, 0.1);
    st = integ.step(m, 0.01);
    EXPECT_TRUE(st.applied);
    EXPECT_TRUE(st.energy_gain);
    EXPECT_FALSE(st.converged);
    EXPECT_GT(st.energy_change_j, 0.0);
    // The next step's balance is about its own (good) solve again.
    st = integ.step(m, 0.01);
    EXPECT_FALSE(st.energy_gain) << st.energy_change_j << " J of " << st.energy_j;
    EXPECT_TRUE(st.converged);
  }
}

// A low iteration cap on a sliver-laden, stiffness-contrast mesh: steps inject energy now and
// then; each such step is flagged (never reported as converged), and the state stays finite.
TEST(DivergenceGuard, CappedSolveThatInjectsEnergyIsFlagged) {
  TetMesh m = soft_bar();
  const FemConfig c = alternating_stiffness(m, 3e7, 0.0, 2, 1e-12);
  ImplicitIntegrator integ(c);
  int flagged = 0;
  for (int s = 0; s < 400; ++s) {
    const StepStatus st = integ.step(m, 0.01);
    ASSERT_TRUE(st.applied);
    if (st.energy_gain) {
      ++flagged;
      EXPECT_FALSE(st.converged);
    }
  }
  for (std::size_t i = 0; i < m.x.size(); ++i) ASSERT_TRUE(m.x[i].allFinite());
  EXPECT_GT(flagged, 0);
}

// SolverSettings::remove_energy_gain: each flagged gain is taken back out of the kinetic energy
// (all of it when the kinetic energy suffices, never more), and nothing is taken when no step is
// flagged. A kick given by hand is a gain like any other.
TEST(DivergenceGuard, RemovingAGainTakesItOutOfTheKineticEnergy) {
  TetMesh m = soft_bar();
  FemConfig c = alternating_stiffness(m, 3e7, 0.0, 2, 1e-12);
  c.solver.remove_energy_gain = true;
  ImplicitIntegrator integ(c);
  int flagged = 0;
  for (int s = 0; s < 400; ++s) {
    const StepStatus st = integ.step(m, 0.01);
    ASSERT_TRUE(st.applied);
    if (!st.energy_gain) {
      EXPECT_EQ(st.energy_removed_j, 0.0) << s;
      continue;
    }
    ++flagged;
    EXPECT_FALSE(st.converged);
    EXPECT_GT(st.energy_removed_j, 0.0) << s;
    EXPECT_LE(st.energy_removed_j, st.energy_change_j * (1.0 + 1e-12)) << s;
  }
  EXPECT_GT(flagged, 0);
  for (std::size_t i = 0; i < m.x.size(); ++i) ASSERT_TRUE(m.x[i].allFinite());

  // A converged run, nearly at rest, then a kick (~0.015 J against ~3e-4 J dissipated per step):
  // the kick's energy is the gain, all of it taken out on the next step.
  TetMesh k = soft_bar();
  FemConfig ck = soft(SolverKind::cholmod);
  ck.solver.remove_energy_gain = true;
  ImplicitIntegrator ik(ck);
  for (int s = 0; s < 300; ++s) ASSERT_EQ(ik.step(k, 0.01).energy_removed_j, 0.0);
  for (std::size_t i = 0; i < k.v.size(); ++i)
    if (k.fixed[i] == 0) k.v[i] += Vec3(0.0, 0.0, 0.1);
  const StepStatus st = ik.step(k, 0.01);
  EXPECT_TRUE(st.energy_gain);
  EXPECT_GT(st.energy_change_j, 0.0);
  EXPECT_NEAR(st.energy_removed_j, st.energy_change_j, 1e-9 * st.energy_change_j);
}

}  // namespace
}  // namespace serosa::fem
