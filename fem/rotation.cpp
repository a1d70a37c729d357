#include "fem/rotation.h"

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

Mat3 robust_rotation(const Mat3& f, Quat& q, int max_iter) {
  if (extract_rotation(f, q, max_iter)) return q.toRotationMatrix();
  const Mat3 r = polar_rotation_svd(f);
  if (!r.allFinite()) {  // NaN in F: keep the last rotation
    return q.toRotationMatrix();
  }
  q = Quat(r);
  q.normalize();
  return r;
}

}  // namespace serosa::fem
