// fem/elastic_forces.h and fem/tet_element.h against analysis: rigid motions are force-free
// (corotational only), affine displacements give constant stress (patch test), and the element
// stiffness is the derivative of the force (finite differences).
#include "fem/elastic_forces.h"

#include <gtest/gtest.h>

#include <random>
#include <vector>

#include "fem/fem_elements.h"
#include "fem/rotation.h"
#include "fem_fixtures.h"

namespace serosa::fem {
namespace {

FemConfig config_e(double young, double nu) {
  FemConfig c;
  c.default_material.young_pa = young;
  c.default_material.poisson = nu;
  return c;
}

std::vector<Mat3> rotations_of(const TetMesh& mesh, const FemElements& el) {
  std::vector<Quat> q(static_cast<std::size_t>(mesh.num_tets()), Quat::Identity());
  std::vector<Mat3> r(q.size());
  update_rotations(mesh, el, q, r, 100);
  return r;
}

double max_norm(const std::vector<Vec3>& f) {
  double m = 0.0;
  for (const Vec3& v : f) m = std::max(m, v.norm());
  return m;
}

class RigidMotion : public ::testing::TestWithParam<int> {};  // random seed

TEST_P(RigidMotion, CorotationalForcesVanishLinearDoNot) {
  std::mt19937 rng(static_cast<std::uint32_t>(GetParam()));
  TetMesh mesh = test_meshes::kuhn_bar(3, 2, 2, 0.01, 0.01, 0.01);
  fixtures::jitter_interior(mesh, 0, 0.03, 0, 0.02, 0, 0.02, 0.002, 1);
  const FemConfig cfg = config_e(1e4, 0.45);
  FemElements el;
  build_elements(mesh, cfg, el);
  for (int k = 0; k < 10; ++k) {
    const Mat3 q = fixtures::random_rotation(rng);
    const Vec3 c(0.1, -0.2, 0.3);
    for (std::size_t i = 0; i < mesh.rest.size(); ++i) mesh.x[i] = q * mesh.rest[i] + c;
    const double angle = Eigen::AngleAxisd(q).angle();
    std::vector<Vec3> f(mesh.rest.size());
    corotational_forces(mesh, el, rotations_of(mesh, el), f);
    // Scale: a 1% strain on one element gives E * h^2 * 1e-2 = 1e-2 N.
    EXPECT_LE(max_norm(f), 1e-9 * 1e4 * 1e-4) << "angle " << angle;
    linear_forces(mesh, el, f);
    if (angle > 0.1) {
      EXPECT_GT(max_norm(f), 1e-3 * 1e4 * 1e-4 * angle) << "angle " << angle;
    }
  }
}

INSTANTIATE_TEST_SUITE_P(Seeds, RigidMotion, ::testing::Values(1, 2, 3, 4, 5));

TEST(PatchTest, AffineDisplacementGivesConstantStressAndFreeInteriorNodes) {
  TetMesh mesh = test_meshes::kuhn_bar(4, 4, 4, 0.25, 0.25, 0.25);
  fixtures::jitter_interior(mesh, 0, 1, 0, 1, 0, 1, 0.06, 42);
  const FemConfig cfg = config_e(5e3, 0.3);
  FemElements el;
  build_elements(mesh, cfg, el);
  Mat3 a;
  a << 1.02, 0.01, -0.015, 0.005, 0.99, 0.02, -0.01, 0.0, 1.01;
  const Vec3 c(0.3, 0.1, -0.2);
  for (std::size_t i = 0; i < mesh.rest.size(); ++i) mesh.x[i] = a * mesh.rest[i] + c;

  // Linear FEM: every tet's strain is sym(A) - I; interior nodes feel no force.
  std::vector<Vec3> f(mesh.rest.size());
  linear_forces(mesh, el, f);
  const Vec3 lo(0, 0, 0), hi(1, 1, 1);
  int interior = 0;
  for (std::size_t i = 0; i < f.size(); ++i)
    if (!fixtures::on_box_boundary(mesh.rest[i], lo, hi)) {
      EXPECT_LE(f[i].norm(), 1e-10 * 5e3 * 0.0625) << i;
      ++interior;
    }
  EXPECT_EQ(interior, 27);
  // Boundary forces sum to zero (equilibrium of a constant stress field).
  Vec3 total = Vec3::Zero();
  for (const Vec3& fi : f) total += fi;
  EXPECT_LE(total.norm(), 1e-10);

  // Corotational: every tet has the same F = A, hence the same R and stress.
  const std::vector<Mat3> r = rotations_of(mesh, el);
  const Mat3 r0 = polar_rotation_svd(a);
  for (const Mat3& rt : r) EXPECT_LE((rt - r0).norm(), 1e-8);
  corotational_forces(mesh, el, r, f);
  for (std::size_t i = 0; i < f.size(); ++i)
    if (!fixtures::on_box_boundary(mesh.rest[i], lo, hi)) {
      EXPECT_LE(f[i].norm(), 1e-10 * 5e3);
    }
  // Virtual work: sum_a f_a X_a^T = -sum_e V_e R sigma sum_a b_a X_a^T = -V_total R sigma,
  // with sigma from the rotated-back strain sym(R^T A) - I.
  const Mat3 g = r0.transpose() * a - Mat3::Identity();
  const Mat3 sigma = linear_stress(el.elements[0], 0.5 * (g + g.transpose()));
  Mat3 work = Mat3::Zero();
  for (std::size_t i = 0; i < f.size(); ++i) work += f[i] * mesh.rest[i].transpose();
  EXPECT_LE((work + r0 * sigma).norm(), 1e-9 * sigma.norm());
}

TEST(TetElement, StiffnessIsTheDerivativeOfLinearForce) {
  TetMesh mesh;
  mesh.add_node(Vec3(0, 0, 0));
  mesh.add_node(Vec3(0.1, 0.01, 0));
  mesh.add_node(Vec3(0.02, 0.09, 0.01));
  mesh.add_node(Vec3(0.01, 0.02, 0.11));
  mesh.add_tet({0, 1, 2, 3}, 1);
  FemElements el;
  build_elements(mesh, config_e(1e5, 0.35), el);
  ASSERT_TRUE(el.elements[0].active());
  std::mt19937 rng(2);
  std::uniform_real_distribution<double> u(-1e-3, 1e-3);
  for (auto& x : mesh.x) x += Vec3(u(rng), u(rng), u(rng));
  std::vector<Vec3> f0(4), f1(4);
  linear_forces(mesh, el, f0);
  for (int b = 0; b < 4; ++b)
    for (int j = 0; j < 3; ++j) {
      const double h = 1e-6;
      mesh.x[static_cast<std::size_t>(b)][j] += h;
      linear_forces(mesh, el, f1);
      mesh.x[static_cast<std::size_t>(b)][j] -= h;
      for (int a = 0; a < 4; ++a) {
        // df_a / dx_b = -K_ab (linear: exact up to round-off)
        const Vec3 col = -stiffness_block(el.elements[0], a, b).col(j);
        const Vec3 fd = (f1[static_cast<std::size_t>(a)] - f0[static_cast<std::size_t>(a)]) / h;
        EXPECT_LE((fd - col).norm(), 1e-5 * (1.0 + col.norm())) << a << " " << b << " " << j;
      }
    }
  // K is symmetric: K_ab = K_ba^T.
  for (int a = 0; a < 4; ++a)
    for (int b = 0; b < 4; ++b)
      EXPECT_LE((stiffness_block(el.elements[0], a, b) -
                 stiffness_block(el.elements[0], b, a).transpose())
                    .norm(),
                1e-9);
}

TEST(FemElements, LumpedMassSumsToDensityTimesVolume) {
  TetMesh mesh = test_meshes::kuhn_bar(3, 2, 1, 0.1, 0.2, 0.3);
  FemConfig cfg;
  cfg.default_material.density_kgpm3 = 1200.0;
  FemElements el;
  build_elements(mesh, cfg, el);
  double total = 0.0;
  for (double m : el.node_mass) total += m;
  EXPECT_NEAR(total, 1200.0 * 0.3 * 0.4 * 0.3, 1e-12);
  for (const TetElement& e : el.elements) EXPECT_GT(e.volume_m3, 0.0);
}

}  // namespace
}  // namespace serosa::fem
