// Stability after many cuts: a bar changed by 50 random cut-like topology deltas
// (tets removed, or split at a random interior point into four, slivers included: synthetic,
// because real scissor cuts of serosa::cutting grew a 24-tet bar to 357k tets in 47 cuts at the
// time of writing, too large for a unit test), then run for 10,000 steps: every
// step is applied with a clear status (converged, or the iteration cap reached and said so),
// positions and velocities stay finite, and the energy (kinetic + elastic; gravity cancelled
// for the long run, since pieces cut free would fall forever) never exceeds what the bar had
// when the long run started (Rayleigh damping 0.1 / 0.1 only dissipates).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <random>
#include <vector>

#include "engine/topology_delta.h"
#include "fem/implicit_integrator.h"
#include "fem/rotation.h"
#include "fem_energy.h"
#include "fem_fixtures.h"

namespace serosa::fem {
namespace {

double energy(const TetMesh& m, const FemElements& el) {
  return fixtures::kinetic_energy(m) + fixtures::elastic_energy(m, el);
}

// A cut-like delta: removes 1-4 random tets; each is dropped (a gap opens, holes are filled by
// moves) or split into four around a new node at random barycentric weights (often a sliver).
TopologyDelta cut_like(const TetMesh& m, std::mt19937& rng) {
  TopologyDelta d;
  std::uniform_int_distribution<int> tet(0, m.num_tets() - 1);
  std::uniform_int_distribution<int> count(1, 4);
  std::uniform_real_distribution<double> w(1e-4, 1.0);
  std::vector<std::int32_t> removed;
  const int k = count(rng);
  while (static_cast<int>(removed.size()) < k) {
    const std::int32_t t = tet(rng);
    if (std::find(removed.begin(), removed.end(), t) == removed.end()) removed.push_back(t);
  }
  std::sort(removed.begin(), removed.end());
  d.removed_tets = removed;
  std::bernoulli_distribution split(0.8);
  for (std::int32_t t : removed) {
    if (!split(rng)) continue;
    const Tet& n = m.tets[static_cast<std::size_t>(t)];
    NodeParent p;
    p.count = 4;
    p.nodes = n;
    double sum = 0.0;
    for (double& x : p.weights) sum += (x = w(rng) * w(rng));
    for (double& x : p.weights) x /= sum;
    const auto c =
        static_cast<std::int32_t>(m.num_nodes() + static_cast<int>(d.added_nodes.size()));
    d.added_nodes.push_back(p);
    for (std::size_t i = 0; i < 4; ++i) {
      Tet sub = n;
      sub[i] = c;
      d.added_tets.push_back(sub);
      d.added_groups.push_back(m.group[static_cast<std::size_t>(t)]);
    }
  }
  return d;
}

TEST(CutsThenLongRun, FiftyCutsThenTenThousandSteps) {
#if defined(__SANITIZE_ADDRESS__)
  const int long_steps = 2000;  // ASan is ~5x slower; the release run does all 10,000
#else
  const int long_steps = 10000;
#endif
  std::mt19937 rng(4242);
  TetMesh m = test_meshes::kuhn_bar(6, 2, 2, 0.05, 0.05, 0.05);
  m.fill_node_state();
  fixtures::clamp_x0(m);
  FemConfig c;
  c.default_material = FemMaterial{3000.0, 0.45, 1000.0, 0.1, 0.1};
  c.solver.kind = SolverKind::pcg;
  c.solver.tolerance = 1e-6;
  c.solver.max_iterations = 100;
  ImplicitIntegrator integ(c);
  const double dt = 0.01;
  const auto check = [&](const StepStatus& st) {
    ASSERT_TRUE(st.applied);
    ASSERT_TRUE(std::isfinite(st.residual));
    if (!st.converged) {
      ASSERT_EQ(st.iterations, c.solver.max_iterations);
    }
  };
  ASSERT_TRUE(integ.step(m, dt).applied);
  int cuts = 0;
  for (int k = 0; k < 50; ++k) {
    TopologyDelta d = cut_like(m, rng);
    if (!d.empty()) {
      apply(m, d);
      integ.update(m, d);
      ++cuts;
    }
    check(integ.step(m, dt));
    if (HasFatalFailure()) return;
  }
  EXPECT_EQ(cuts, 50);
  std::printf("after %d cuts: %d tets, %d nodes\n", cuts, m.num_tets(), m.num_nodes());
  std::fflush(stdout);
  std::vector<Vec3> anti_g(m.x.size());
  for (std::size_t i = 0; i < m.x.size(); ++i) anti_g[i] = -m.mass[i] * c.gravity_mps2;
  const double e0 = energy(m, integ.elements());
  int unconverged = 0;
  for (int s = 0; s < long_steps; ++s) {
    const StepStatus st = integ.step(m, dt, anti_g);
    check(st);
    if (HasFatalFailure()) return;
    unconverged += st.converged ? 0 : 1;
    if (s % 100 == 99) {
      for (std::size_t i = 0; i < m.x.size(); ++i) {
        ASSERT_TRUE(m.x[i].allFinite() && m.v[i].allFinite()) << "step " << s;
      }
      ASSERT_LE(energy(m, integ.elements()), e0 * (1.0 + 1e-3) + 1e-12) << "step " << s;
    }
  }
  std::printf("long run: %d steps, %d not converged (cap %d)\n", long_steps, unconverged,
              c.solver.max_iterations);
}

}  // namespace
}  // namespace serosa::fem
