// Energy behaviour of the implicit step: an undamped free vibration never gains
// energy (backward Euler only dissipates).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <vector>

#include "fem/implicit_integrator.h"
#include "fem/rotation.h"
#include "fem_energy.h"
#include "fem_fixtures.h"

namespace serosa::fem {
namespace {

using fixtures::elastic_energy;
using fixtures::kinetic_energy;

// An undamped clamped beam set swinging by an initial velocity (tip at 0.5 m/s, a swing of about
// a quarter of its length that rotates its elements): kinetic + elastic energy never increases from
// one step to the next (to 1e-6 of the initial energy: solver tolerance and the frozen rotations of
// the linearized step), for small and large dt, with CHOLMOD and with CG.
TEST(FreeVibration, UndampedNeverGainsEnergy) {
  for (SolverKind kind : {SolverKind::cholmod, SolverKind::pcg}) {
    for (double dt : {1e-3, 1e-2}) {
      SCOPED_TRACE(testing::Message() << "solver " << static_cast<int>(kind) << " dt " << dt);
      TetMesh m = test_meshes::kuhn_bar(10, 2, 2, 0.01, 0.01, 0.01);
      m.fill_node_state();
      fixtures::clamp_x0(m);
      FemConfig c;
      c.default_material = FemMaterial{1e5, 0.3, 1000.0, 0.0, 0.0};
      c.gravity_on = false;
      c.solver.kind = kind;
      c.solver.tolerance = 1e-10;
      c.solver.max_iterations = 2000;
      ImplicitIntegrator integ(c);
      ASSERT_TRUE(integ.step(m, dt).applied);  // at rest, no load: builds the masses, stays put
      for (std::size_t i = 0; i < m.x.size(); ++i) {
        const double s = m.rest[i].x() / 0.1;
        if (m.fixed[i] == 0) m.v[i] = Vec3(0.0, 0.5 * s * s, 0.1 * s);
      }
      integ.restart_energy_balance();  // v set by hand: not a gain of the last step
      const double e0 = kinetic_energy(m) + elastic_energy(m, integ.elements());
      ASSERT_GT(e0, 0.0);
      double prev = e0, max_swing = 0.0;
      const int steps = static_cast<int>(0.3 / dt);
      for (int s = 0; s < steps; ++s) {
        const StepStatus st = integ.step(m, dt);
        ASSERT_TRUE(st.applied);
        ASSERT_TRUE(st.converged);
        const double e = kinetic_energy(m) + elastic_energy(m, integ.elements());
        ASSERT_LE(e, prev + 1e-6 * e0) << "step " << s;
        prev = e;
        for (std::size_t i = 0; i < m.x.size(); ++i)
          max_swing = std::max(max_swing, (m.x[i] - m.rest[i]).norm());
      }
      EXPECT_LT(prev, e0);
      EXPECT_GT(max_swing, 0.01);  // it really swung (10% of its length)
    }
  }
}

}  // namespace
}  // namespace serosa::fem
