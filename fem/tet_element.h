// TetElement: the rest-state data of one linear tetrahedron (precomputed once per tet and topology
// change) and the closed-form linear stiffness built from it.
//
// Linear shape functions N_a (a = 0..3) have constant gradients b_a = grad N_a (1/m):
//   D_m = [X_1 - X_0, X_2 - X_0, X_3 - X_0]   (rest shape matrix, m)
//   b_a = row a-1 of D_m^{-1}  (a = 1..3),   b_0 = -(b_1 + b_2 + b_3)
// so the deformation gradient is F = sum_a x_a b_a^T = D_s D_m^{-1}.
// Linear isotropic elasticity, small strain eps = sym(grad u), sigma = lambda tr(eps) I + 2 mu eps,
// gives the 3x3 block (a, b) of the 12x12 element stiffness (N/m):
//   K_ab = V (lambda b_a b_b^T + mu b_b b_a^T + mu (b_a . b_b) I)
// and the nodal elastic force f_a = -V sigma b_a.
#pragma once

#include <array>

#include "engine/math.h"
#include "fem/fem_config.h"

namespace serosa::fem {

struct TetElement {
  Tet nodes{-1, -1, -1, -1};   ///< (4) node ids it was built for (lets a delta subtract its mass)
  std::array<Vec3, 4> grad{};  ///< (4 x 3) shape-function gradients b_a in rest space, 1/m
  double volume_m3 = 0.0;      ///< rest volume V, m^3 (0 for a degenerate tet: inactive)
  double lambda_pa = 0.0;      ///< first Lamé parameter of its material, Pa
  double mu_pa = 0.0;          ///< shear modulus of its material, Pa
  double beta_s = 0.0;         ///< Rayleigh stiffness damping of its material, s
  double alpha_hz = 0.0;       ///< Rayleigh mass damping of its material, 1/s
  double mass_kg = 0.0;        ///< rho V, kg (lumped a quarter to each node)

  [[nodiscard]] bool active() const { return volume_m3 > 0.0; }
};

/// Rest volumes below this many m^3 make a tet inactive (no stiffness, no mass); cutting can
/// produce slivers this thin and D_m^{-1} would overflow.
inline constexpr double kMinElementVolume = 1e-24;

/// Precomputes the element of the tet with rest nodes (X_0..X_3) and material `mat`.
[[nodiscard]] TetElement make_element(const Vec3& x0, const Vec3& x1, const Vec3& x2,
                                      const Vec3& x3, const FemMaterial& mat);

/// Block (a, b) of the linear element stiffness K_ab (formula above), N/m.
[[nodiscard]] Mat3 stiffness_block(const TetElement& e, int a, int b);

/// Cauchy stress of linear elasticity for strain eps (3x3, symmetric): lambda tr(eps) I + 2 mu eps.
[[nodiscard]] inline Mat3 linear_stress(const TetElement& e, const Mat3& eps) {
  return e.lambda_pa * eps.trace() * Mat3::Identity() + 2.0 * e.mu_pa * eps;
}

/// Deformation gradient F = sum_a p_a b_a^T of the nodal vectors p (positions, velocities, ...).
[[nodiscard]] inline Mat3 nodal_gradient(const TetElement& e, const Vec3& p0, const Vec3& p1,
                                         const Vec3& p2, const Vec3& p3) {
  return p0 * e.grad[0].transpose() + p1 * e.grad[1].transpose() + p2 * e.grad[2].transpose() +
         p3 * e.grad[3].transpose();
}

}  // namespace serosa::fem
