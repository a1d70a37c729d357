// Rotational part of a deformation gradient: R in SO(3) (never a reflection) maximizing
// tr(R^T F), which is the polar factor of F when det F > 0 and its reflection-free
// generalization (Irving et al. 2004, "Invertible finite elements") when the tet is inverted.
//
// Two methods, same answer:
//  * extract_rotation(): Müller, Bender, Chentanez, Macklin 2016, "A robust method to extract the
//    rotational part of deformations". Iterates on a unit quaternion q, warm-started from the
//    previous step's rotation:
//        omega = sum_i r_i x f_i / (|sum_i r_i . f_i| + 1e-9)    (r_i, f_i: columns of R(q), F)
//        q <- exp(omega) q
//    omega is the ascent direction of tr(R^T F) on SO(3) scaled by a Newton-like step, so a warm
//    start converges in 1-3 iterations per step. Always returns a rotation (a unit quaternion),
//    for singular F (q unchanged when F = 0) and inverted F alike. Used by the solver: cheap.
//  * polar_rotation_svd(): F = U S V^T, then flip the last column of U (resp. V) when det U < 0
//    (resp. det V < 0), so that R = U V^T has det +1 and the sign goes into the smallest singular
//    value (Irving et al. 2004, section 5). The reference the tests compare against.
#pragma once

#include "engine/math.h"

namespace serosa::fem {

/// Iterations extract_rotation() runs at most unless told otherwise.
inline constexpr int kRotationMaxIterations = 20;

/// Müller et al. 2016: refines q (unit quaternion, in and out) towards the rotation maximizing
/// tr(R(q)^T F). F: (3 x 3) deformation gradient. Stops when the step angle |omega| < 1e-9 rad
/// (returns true) or after max_iter (returns false). Convergence is linear: the step
/// omega ~ torque / tr(F) undershoots the Newton step torque / (s_j + s_k) (s: singular values),
/// so each iteration shrinks the error by about 1 - (s_j + s_k) / tr: ~1/3 for a mild stretch,
/// but barely at all when F is nearly flat (s_j + s_k << tr). Hence the fallback below.
bool extract_rotation(const Mat3& f, Quat& q, int max_iter = kRotationMaxIterations);

/// Newton's method on the same objective, warm-started from q like extract_rotation(). With
/// A = F R^T, the gradient of tr(R^T F) over left rotations exp(w) R is the torque
/// t = sum_i r_i x f_i and its Hessian is -(tr(A) I - sym(A)); where that 3x3 matrix is positive
/// definite (every non-inverted F near its rotation), the step w = (tr(A) I - sym(A))^{-1} t
/// converges quadratically (1-2 iterations per solver step from a warm start instead of ~10 for
/// Müller's scalar step, which is tr(A) I in place of the matrix). Elsewhere (inverted or far from
/// the answer) it takes Müller's step, which always ascends. Same fixed point, same return value.
/// Stops when Müller's step is below `tolerance` rad (the Newton error is about 2/3 of it), or
/// right after a Newton step below sqrt(tolerance) rad on a well-conditioned Hessian (its error
/// is then ~ its square; measured at most 8e-5 of the tolerance, fem/rotation.cpp).
bool newton_rotation(const Mat3& f, Quat& q, int max_iter = kRotationMaxIterations,
                     double tolerance = 1e-9);

/// Irving et al. 2004: reflection-free polar rotation of F (3 x 3) from its SVD.
[[nodiscard]] Mat3 polar_rotation_svd(const Mat3& f);

/// What the solver uses per tet and step: newton_rotation() warm-started from q with at most
/// max_iter iterations; if it has not converged by then (nearly flat or freshly inverted tets),
/// the SVD answer instead. q is updated to the returned rotation.
Mat3 robust_rotation(const Mat3& f, Quat& q, int max_iter = kRotationMaxIterations,
                     double tolerance = 1e-9);

/// The rotation of one tet for one solver step. q: in, the rotation of the last step; out, this
/// step's. q_prev: the rotation a step before that.
/// - Upright tets (det F > 0): robust_rotation() from the rotation extrapolated from the last two
///   steps, q (q_prev^* q), which halves the Newton iterations on a moving body.
/// - Inverted tets (det F <= 0): newton_rotation() from the last rotation as it is, with no SVD
///   fallback. Inside out, the maximizer of tr(R^T F) is
///   ill-determined where the two smaller signed singular values nearly cancel (a crushed or a
///   cut sliver): the extrapolated start and the SVD's global answer flipped such tets by up to
///   70 degrees every step, back and forth, and each flip changes the system matrix, which the
///   lagged factor then no longer fits. Started from the last rotation and kept near it, the
///   rotation follows the tet continuously.
Mat3 step_rotation(const Mat3& f, Quat& q, const Quat& q_prev, double tolerance);

/// Rotation tolerance of the implicit step, rad: a 1e-7 rad error in R_e changes the elastic
/// force by ~1e-7 of the element's stress scale, far below any CG tolerance used; it saves one
/// Newton iteration per tet and step against 1e-9.
inline constexpr double kStepRotationTolerance = 1e-7;

}  // namespace serosa::fem
