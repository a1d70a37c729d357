// Plasticity (Müller & Gross 2004, fem_config.h PlasticitySettings): a bar pulled beyond the
// elastic limit keeps a permanent elongation once released; below the limit, or with plasticity
// off, it returns to its rest length.
#include <gtest/gtest.h>

#include <vector>

#include "fem/implicit_integrator.h"
#include "fem_fixtures.h"

namespace serosa::fem {
namespace {

// Mean x displacement of the free end (x = 0.8 m) after pulling it with `force` N along +x for
// 3 s and releasing it for 5 s. Bar 0.8 x 0.1 x 0.1 m, x = 0 clamped, E = 1e4 Pa: axial strain
// ~ force / 100.
double set_after_release(double force, bool plastic, double* loaded = nullptr) {
  TetMesh m = test_meshes::kuhn_bar(8, 1, 1, 0.1, 0.1, 0.1);
  m.fill_node_state();
  std::vector<std::size_t> end;
  for (std::size_t i = 0; i < m.rest.size(); ++i) {
    m.fixed[i] = m.rest[i].x() < 1e-12 ? 1 : 0;
    if (m.rest[i].x() > 0.8 - 1e-9) end.push_back(i);
  }
  FemConfig c;
  c.default_material = FemMaterial{1e4, 0.3, 1000.0, 10.0, 0.0};
  c.gravity_on = false;
  c.solver.kind = SolverKind::cholmod;
  c.plasticity = PlasticitySettings{plastic, 0.05, 2.0, 0.3};
  ImplicitIntegrator integ(c);
  std::vector<Vec3> f(m.rest.size(), Vec3::Zero());
  for (std::size_t i : end) f[i] = Vec3(force / static_cast<double>(end.size()), 0.0, 0.0);
  const auto disp = [&] {
    double s = 0.0;
    for (std::size_t i : end) s += m.x[i].x() - m.rest[i].x();
    return s / static_cast<double>(end.size());
  };
  for (int s = 0; s < 150; ++s) EXPECT_TRUE(integ.step(m, 0.02, f).applied);
  if (loaded != nullptr) *loaded = disp();
  for (int s = 0; s < 250; ++s) EXPECT_TRUE(integ.step(m, 0.02).applied);
  for (const Vec3& x : m.x) EXPECT_TRUE(x.allFinite());
  if (plastic) {
    for (const Mat3& ep : integ.plastic_strain()) EXPECT_LE(ep.norm(), 0.3 + 1e-12);  // capped
  }
  return disp();
}

TEST(Plasticity, LoadBeyondTheElasticLimitLeavesAPermanentSet) {
  double loaded = 0.0;
  const double set = set_after_release(10.0, true, &loaded);  // strain ~0.1 > yield 0.05
  EXPECT_GT(loaded, 0.05);
  EXPECT_GT(set, 0.1 * loaded);
  EXPECT_LT(set, loaded);
}

TEST(Plasticity, LoadBelowTheLimitOrPlasticityOffLeavesNone) {
  double loaded = 0.0;
  const double below = set_after_release(2.0, true, &loaded);  // strain ~0.02 < yield
  EXPECT_GT(loaded, 0.005);
  EXPECT_LT(std::abs(below), 1e-3 * loaded);
  const double off = set_after_release(10.0, false, &loaded);
  EXPECT_LT(std::abs(off), 1e-3 * loaded);
}

}  // namespace
}  // namespace serosa::fem
