// Corotational elastic forces (Müller & Gross 2004, "Interactive Virtual Materials", eq. 7):
//   f_e = -R_e K_e (R_e^T x - x_0)
// evaluated through the stress instead of the 12x12 matrix (same result, 10x fewer flops): with
// F = sum_b x_b b_b^T and the rotated-back strain  E = sym(R^T F) - I,
//   f_a = -V R sigma(E) b_a,   sigma(E) = lambda tr(E) I + 2 mu E.
// Linear FEM is the same with R = I, which is not invariant under rotation (the tests show it).
#pragma once

#include <span>

#include "engine/tet_mesh.h"
#include "fem/fem_elements.h"

namespace serosa::fem {

/// Per-tet rotation of the current positions mesh.x: F_e = D_s D_m^{-1}, R_e from
/// robust_rotation() (fem/rotation.h: Müller et al. 2016 warm-started from q, SVD fallback). q: (m)
/// unit quaternions, in/out; rot: (m) out. Inactive (degenerate) tets get the identity. Returns the
/// number of inverted tets (det F <= 0).
int update_rotations(const TetMesh& mesh, const FemElements& el, std::span<Quat> q,
                     std::span<Mat3> rot, int max_iter);

/// Element force on its 4 nodes with a velocity (stiffness-damping) term folded in:
///   f_a = -V R sigma(sym(R^T F) - I + k_v sym(R^T F_v)) b_a,  F_v = sum_b v_b b_b^T
/// i.e. -R K (R^T x - x0) - k_v R K R^T v. out: (4) forces on the tet's corners, N.
/// plastic: the tet's plastic strain eps_p (symmetric), subtracted from the strain; or null.
void element_forces(const TetElement& e, const Mat3& r, const Tet& tet, std::span<const Vec3> x,
                    std::span<const Vec3> v, double k_v, std::span<Vec3, 4> out,
                    const Mat3* plastic = nullptr);

/// Corotated elastic energy of one element for deformation gradient f and rotation r:
///   V (mu eps:eps + lambda/2 tr(eps)^2),  eps = sym(R^T F) - I (- eps_p when plastic), J.
/// With r the polar rotation of f this is the energy the elastic forces derive from; with r
/// frozen over a step it is the energy of the step's linear model (the divergence guard).
[[nodiscard]] double corotated_energy(const TetElement& e, const Mat3& r, const Mat3& f,
                                      const Mat3* plastic = nullptr);

/// element_forces() and corotated_energy() of one tet in one pass, from its deformation gradient
/// f (F of the positions) and fv (F of the velocities), each computed once by the caller: fills
/// out (4, N) as element_forces() does and returns the corotated energy (J) at f.
double element_forces_energy(const TetElement& e, const Mat3& r, const Mat3& f, const Mat3& fv,
                             double k_v, std::span<Vec3, 4> out, const Mat3* plastic = nullptr);

/// Total elastic forces f (n) = sum_e -R_e K_e (R_e^T x - x0), N, for the given rotations (m).
/// Serial reference for tests and tools (the step gathers in parallel).
void corotational_forces(const TetMesh& mesh, const FemElements& el, std::span<const Mat3> rot,
                         std::span<Vec3> f);

/// Linear FEM forces f (n) = -K (x - x0): corotational_forces with R = I.
void linear_forces(const TetMesh& mesh, const FemElements& el, std::span<Vec3> f);

}  // namespace serosa::fem
