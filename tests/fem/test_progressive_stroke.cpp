// A scissors stroke cut progressively (cutting::ProgressiveCut) while the FEM runs: a clamped bar
// sagging under gravity, one FEM step after each of the stroke's 20 thin steps (the state updated
// locally, ImplicitIntegrator::update). Each step replaces the stroke's pieces by new ones made
// from the pre-stroke tets' nodes where they are now, and releases the previous pieces' nodes.
// Checked: every step applied with finite state; every released node left in no tet is massless
// and stays where it was released with zero velocity; every node in a tet has mass; the total
// mass is the density times the rest volume; the bar ends in two pieces; then, gravity cancelled,
// 150 steps never raise the energy (kinetic + elastic) above what it was after the stroke.
#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "cutting/progressive_cut.h"
#include "cutting/validate.h"
#include "engine/topology_delta.h"
#include "fem/implicit_integrator.h"
#include "fem_energy.h"
#include "fem_fixtures.h"

namespace serosa::fem {
namespace {

TEST(ProgressiveStroke, TwentyThinStepsWithTheFemRunningBetweenThem) {
  TetMesh m = test_meshes::kuhn_bar(6, 2, 2, 0.05, 0.05, 0.05);  // 0.3 x 0.1 x 0.1 m
  m.fill_node_state();
  fixtures::clamp_x0(m);
  FemConfig c;
  c.default_material = FemMaterial{1.0e6, 0.45, 1000.0, 0.1, 0.1};
  c.solver.kind = SolverKind::pcg;
  c.solver.tolerance = 1e-8;
  c.solver.max_iterations = 400;
  ImplicitIntegrator integ(c);
  const double dt = 0.01;
  for (int s = 0; s < 5; ++s) ASSERT_TRUE(integ.step(m, dt).applied);  // sagging

  // The blade: hinged beside the bar at x = 0.17 m, 0.25 m long, closing through 170 degrees in
  // a tilted plane, in 20 thin steps.
  const Vec3 n = Vec3(1.0, 0.15, -0.1).normalized(), hinge(0.17, -0.08, 0.05);
  const Vec3 a = n.unitOrthogonal(), b = n.cross(a);
  auto tip = [&](double t) -> Vec3 { return hinge + 0.25 * (std::cos(t) * a + std::sin(t) * b); };
  const double a0 = 85.0 * 3.141592653589793 / 180.0;
  cutting::ProgressiveCut stroke;
  std::vector<std::pair<std::int32_t, Vec3>> released;  // node, where it was released
  for (int k = 0; k < 20; ++k) {
    const cutting::ConvexPolygon blade(
        {hinge, tip(a0 - 2.0 * a0 * k / 20.0), tip(a0 - 2.0 * a0 * (k + 1) / 20.0)});
    const std::int32_t n_before = m.num_nodes();
    const cutting::CutResult r = stroke.cut(m, blade);
    TopologyDelta d = r.delta;
    apply(m, d);
    stroke.applied(m, d);
    integ.update(m, d);
    ASSERT_EQ(r.stats.degenerate_tets, 0) << "step " << k;
    // The nodes this step released: the previous step's new nodes.
    const std::int64_t rel = stroke.last_step().nodes_released;
    const std::int32_t first = n_before - static_cast<std::int32_t>(rel);
    for (std::int32_t i = first; i < n_before; ++i)
      released.emplace_back(i, m.x[static_cast<std::size_t>(i)]);
    const StepStatus st = integ.step(m, dt);
    ASSERT_TRUE(st.applied) << "step " << k;
    for (std::size_t i = 0; i < m.x.size(); ++i)
      ASSERT_TRUE(m.x[i].allFinite() && m.v[i].allFinite()) << "step " << k << ", node " << i;
  }
  EXPECT_TRUE(stroke.last_step().extended);
  EXPECT_EQ(cutting::count_components(m), 2);
  std::vector<char> used(m.x.size(), 0);
  for (const Tet& t : m.tets)
    for (std::int32_t v : t) used[static_cast<std::size_t>(v)] = 1;
  std::size_t unused = 0;
  for (std::size_t i = 0; i < used.size(); ++i) {
    if (used[i]) {
      EXPECT_GT(m.mass[i], 0.0) << "node " << i;
    } else {
      ++unused;
      EXPECT_EQ(m.mass[i], 0.0) << "node " << i;
      EXPECT_EQ(m.v[i], Vec3::Zero()) << "node " << i;
    }
  }
  EXPECT_EQ(unused, released.size());
  for (const auto& [i, x] : released) EXPECT_EQ(m.x[static_cast<std::size_t>(i)], x) << i;
  double mass = 0.0, volume = 0.0;
  for (double mi : m.mass) mass += mi;
  for (std::int32_t t = 0; t < m.num_tets(); ++t) volume += m.rest_volume(t);
  EXPECT_NEAR(volume, 0.3 * 0.1 * 0.1, 1e-12);
  EXPECT_NEAR(mass, 1000.0 * volume, 1e-9 * 1000.0 * volume);

  // Gravity cancelled: the energy never rises above its value after the stroke.
  std::vector<Vec3> anti_g(m.x.size());
  for (std::size_t i = 0; i < m.x.size(); ++i) anti_g[i] = -m.mass[i] * c.gravity_mps2;
  const auto energy = [&] {
    return fixtures::kinetic_energy(m) + fixtures::elastic_energy(m, integ.elements());
  };
  const double e0 = energy();
  for (int s = 0; s < 150; ++s) {
    const StepStatus st = integ.step(m, dt, anti_g);
    ASSERT_TRUE(st.applied) << s;
    EXPECT_FALSE(st.energy_gain) << s;
    if (s % 20 == 19) {
      ASSERT_LE(energy(), e0 * (1.0 + 1e-6) + 1e-12) << "step " << s;
    }
  }
}

}  // namespace
}  // namespace serosa::fem
