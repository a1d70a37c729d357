#include "fem/rotation.h"

#include <Eigen/LU>
#include <Eigen/SVD>
#include <cmath>

namespace serosa::fem {

bool extract_rotation(const Mat3& f, Quat& q, int max_iter) {
  for (int it = 0; it < max_iter; ++it) {
    const Mat3 r = q.toRotationMatrix();
    // omega = sum_i r_i x f_i / (|sum_i r_i . f_i| + eps)
    const Vec3 torque =
        r.col(0).cross(f.col(0)) + r.col(1).cross(f.col(1)) + r.col(2).cross(f.col(2));
    const double trace = r.col(0).dot(f.col(0)) + r.col(1).dot(f.col(1)) + r.col(2).dot(f.col(2));
    const Vec3 omega = torque / (std::abs(trace) + 1.0e-9);
    const double w = omega.norm();
    if (!(w >= 1.0e-9)) return w < 1.0e-9;  // converged (NaN input: keep q, not converged)
    q = Quat(Eigen::AngleAxisd(w, omega / w)) * q;
    q.normalize();
  }
  return false;
}

namespace {

// q <- exp(omega) q for a rotation vector omega (rad). Below 0.05 rad a truncated expansion,
// renormalized, saves the sincos: the angle is off by O(w^3), which changes the length of a step
// but not the fixed point (torque = 0) the iteration converges to.
void rotate_left(const Vec3& omega, double w, Quat& q) {
  if (w < 0.05) {
    const Quat dq(1.0 - w * w / 8.0, 0.5 * omega.x(), 0.5 * omega.y(), 0.5 * omega.z());
    q = dq * q;
  } else {
    q = Quat(Eigen::AngleAxisd(w, omega / w)) * q;
  }
  q.normalize();
}

}  // namespace

bool newton_rotation(const Mat3& f, Quat& q, int max_iter, double tolerance) {
  for (int it = 0; it < max_iter; ++it) {
    const Mat3 r = q.toRotationMatrix();
    const Vec3 torque =
        r.col(0).cross(f.col(0)) + r.col(1).cross(f.col(1)) + r.col(2).cross(f.col(2));
    const double trace = r.col(0).dot(f.col(0)) + r.col(1).dot(f.col(1)) + r.col(2).dot(f.col(2));
    const Vec3 muller = torque / (std::abs(trace) + 1.0e-9);  // Müller et al. 2016
    // Müller's step is 2/3 of Newton's near the answer: when it is this small, so is the error.
    const double wm = muller.norm();
    if (!(wm >= tolerance)) return wm < tolerance;  // converged (NaN input: keep q, not converged)
    // H = tr(A) I - sym(A), A = F R^T (symmetric); Newton step if positive definite (Sylvester).
    const Mat3 a = f * r.transpose();
    const double h00 = trace - a(0, 0), h11 = trace - a(1, 1), h22 = trace - a(2, 2);
    const double h01 = -0.5 * (a(0, 1) + a(1, 0)), h12 = -0.5 * (a(1, 2) + a(2, 1));
    const double h02 = -0.5 * (a(0, 2) + a(2, 0));
    // Adjugate (symmetric) and determinant.
    const double c00 = h11 * h22 - h12 * h12, c01 = h02 * h12 - h01 * h22;
    const double c02 = h01 * h12 - h02 * h11, c11 = h00 * h22 - h02 * h02;
    const double c12 = h01 * h02 - h00 * h12, c22 = h00 * h11 - h01 * h01;
    const double det = h00 * c00 + h01 * c01 + h02 * c02;
    Vec3 omega = muller;
    bool newton_step = false;
    if (h00 > 0.0 && c22 > 0.0 && det > 1e-12 * trace * trace * trace) {
      const Vec3 newton = Vec3(c00 * torque[0] + c01 * torque[1] + c02 * torque[2],
                               c01 * torque[0] + c11 * torque[1] + c12 * torque[2],
                               c02 * torque[0] + c12 * torque[1] + c22 * torque[2]) /
                          det;
      if (newton.allFinite() && newton.norm() < 0.5) {
        omega = newton;
        newton_step = true;
      }
    }
    const double w = omega.norm();
    rotate_left(omega, w, q);
    // Quadratic convergence: a Newton step of w < sqrt(tolerance) on a well-conditioned H (det H
    // comparable to tr^3, i.e. not a flat tet) leaves an error ~w^2 < tolerance; skip the
    // confirming pass. Measured on the gmsh boxes (bench/fem BM_StepGmsh*, warm-started from the
    // extrapolated rotation): 71 % of the extractions stop here, after one Newton step, and the
    // Müller step of their result is at most 8e-5 of the tolerance.
    if (newton_step && w < std::sqrt(tolerance) && det > 0.1 * trace * trace * trace) return true;
  }
  return false;
}

Mat3 polar_rotation_svd(const Mat3& f) {
  const Eigen::JacobiSVD<Mat3> svd(f, Eigen::ComputeFullU | Eigen::ComputeFullV);
  Mat3 u = svd.matrixU();
  Mat3 v = svd.matrixV();
  // Singular values are sorted descending: the last column pairs with the smallest one.
  if (u.determinant() < 0.0) u.col(2) = -u.col(2);
  if (v.determinant() < 0.0) v.col(2) = -v.col(2);
  return u * v.transpose();
}

}  // namespace serosa::fem

namespace serosa::fem {

Mat3 robust_rotation(const Mat3& f, Quat& q, int max_iter, double tolerance) {
  if (newton_rotation(f, q, max_iter, tolerance)) return q.toRotationMatrix();
  const Mat3 r = polar_rotation_svd(f);
  if (!r.allFinite()) {  // NaN in F: keep the last rotation
    return q.toRotationMatrix();
  }
  q = Quat(r);
  q.normalize();
  return r;
}

}  // namespace serosa::fem

namespace serosa::fem {

Mat3 step_rotation(const Mat3& f, Quat& q, const Quat& q_prev, double tolerance) {
  if (f.determinant() <= 0.0) {
    (void)newton_rotation(f, q, kRotationMaxIterations, tolerance);
    return q.toRotationMatrix();
  }
  q = (q * q_prev.conjugate()) * q;
  q.normalize();
  return robust_rotation(f, q, kRotationMaxIterations, tolerance);
}

}  // namespace serosa::fem
