#include "fem/tet_element.h"

#include <Eigen/LU>

namespace serosa::fem {

TetElement make_element(const Vec3& x0, const Vec3& x1, const Vec3& x2, const Vec3& x3,
                        const FemMaterial& mat) {
  TetElement e;
  e.lambda_pa = mat.lame_lambda();
  e.mu_pa = mat.lame_mu();
  e.beta_s = mat.damping_stiffness;
  e.alpha_hz = mat.damping_mass;
  Mat3 dm;
  dm.col(0) = x1 - x0;
  dm.col(1) = x2 - x0;
  dm.col(2) = x3 - x0;
  const double vol = dm.determinant() / 6.0;
  if (!(vol > kMinElementVolume)) return e;  // degenerate or inverted at rest: inactive
  const Mat3 inv = dm.inverse();
  e.grad[1] = inv.row(0).transpose();
  e.grad[2] = inv.row(1).transpose();
  e.grad[3] = inv.row(2).transpose();
  e.grad[0] = -(e.grad[1] + e.grad[2] + e.grad[3]);
  e.volume_m3 = vol;
  e.mass_kg = mat.density_kgpm3 * vol;
  return e;
}

Mat3 stiffness_block(const TetElement& e, int a, int b) {
  const Vec3& ba = e.grad[a];
  const Vec3& bb = e.grad[b];
  return e.volume_m3 * (e.lambda_pa * ba * bb.transpose() + e.mu_pa * bb * ba.transpose() +
                        e.mu_pa * ba.dot(bb) * Mat3::Identity());
}

}  // namespace serosa::fem
