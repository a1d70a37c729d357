#include "engine/geometry/rigid_fit.h"

#include <Eigen/SVD>

namespace serosa::geometry {

RigidMotion fit_rigid_motion(const std::vector<Vec3>& from, const std::vector<Vec3>& to) {
  RigidMotion m;
  if (from.empty() || from.size() != to.size()) return m;
  Vec3 cf = Vec3::Zero(), ct = Vec3::Zero();
  for (std::size_t i = 0; i < from.size(); ++i) {
    cf += from[i];
    ct += to[i];
  }
  const double k = static_cast<double>(from.size());
  cf /= k;
  ct /= k;
  Mat3 h = Mat3::Zero();  // cross-covariance sum (from - cf)(to - ct)^T, m^2
  double spread = 0.0;
  for (std::size_t i = 0; i < from.size(); ++i) {
    h += (from[i] - cf) * (to[i] - ct).transpose();
    spread += (from[i] - cf).squaredNorm();
  }
  const Eigen::JacobiSVD<Mat3> svd(h, Eigen::ComputeFullU | Eigen::ComputeFullV);
  const Vec3 s = svd.singularValues();
  // A second singular value near zero: the points lie on a line (or coincide), and the rotation
  // about it is anyone's guess.
  if (from.size() >= 3 && s(1) > 1e-9 * spread) {
    Mat3 v = svd.matrixV();
    const Mat3 u = svd.matrixU();
    if ((v * u.transpose()).determinant() < 0.0) v.col(2) = -v.col(2);  // no reflection
    m.rotation = v * u.transpose();
  }
  m.translation = ct - m.rotation * cf;
  return m;
}

}  // namespace serosa::geometry
