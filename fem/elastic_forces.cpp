#include "fem/elastic_forces.h"
#include "fem/parallel.h"

#include <vector>

#include "fem/rotation.h"

namespace serosa::fem {

int update_rotations(const TetMesh& mesh, const FemElements& el, std::span<Quat> q,
                     std::span<Mat3> rot, int max_iter) {
  int inverted = 0;
#pragma omp parallel for schedule(static) reduction(+ : inverted) if (mesh.num_tets() >= kParallelMin)
  for (std::int32_t t = 0; t < mesh.num_tets(); ++t) {
    const auto ut = static_cast<std::size_t>(t);
    const TetElement& e = el.elements[ut];
    if (!e.active()) {
      rot[ut].setIdentity();
      continue;
    }
    const Tet& n = mesh.tets[ut];
    const Mat3 f = nodal_gradient(e, mesh.x[n[0]], mesh.x[n[1]], mesh.x[n[2]], mesh.x[n[3]]);
    if (f.determinant() <= 0.0) ++inverted;
    rot[ut] = robust_rotation(f, q[ut], max_iter);
  }
  return inverted;
}

void element_forces(const TetElement& e, const Mat3& r, const Tet& tet, std::span<const Vec3> x,
                    std::span<const Vec3> v, double k_v, std::span<Vec3, 4> out,
                    const Mat3* plastic) {
  const Mat3 f = nodal_gradient(e, x[tet[0]], x[tet[1]], x[tet[2]], x[tet[3]]);
  const Mat3 fv = k_v != 0.0 ? nodal_gradient(e, v[tet[0]], v[tet[1]], v[tet[2]], v[tet[3]])
                             : Mat3::Zero().eval();
  (void)element_forces_energy(e, r, f, fv, k_v, out, plastic);
}

namespace {

// eps = sym(G) - I (- eps_p), G = R^T F.
Mat3 corotated_strain(const Mat3& g, const Mat3* plastic) {
  Mat3 eps = 0.5 * (g + g.transpose()) - Mat3::Identity();
  if (plastic != nullptr) eps -= *plastic;
  return eps;
}

// V (mu eps:eps + lambda/2 tr(eps)^2), J.
double strain_energy(const TetElement& e, const Mat3& eps) {
  const double tr = eps.trace();
  return e.volume_m3 * (e.mu_pa * eps.squaredNorm() + 0.5 * e.lambda_pa * tr * tr);
}

}  // namespace

double corotated_energy(const TetElement& e, const Mat3& r, const Mat3& f, const Mat3* plastic) {
  return strain_energy(e, corotated_strain(r.transpose() * f, plastic));
}

double element_forces_energy(const TetElement& e, const Mat3& r, const Mat3& f, const Mat3& fv,
                             double k_v, std::span<Vec3, 4> out, const Mat3* plastic) {
  // P = -V R sigma(eps + k_v sym(R^T F_v)): f_a = P b_a; the energy is of eps alone.
  const Mat3 rt = r.transpose();
  Mat3 eps = corotated_strain(rt * f, plastic);
  const double energy = strain_energy(e, eps);
  if (k_v != 0.0) {
    const Mat3 gv = rt * fv;
    eps += (0.5 * k_v) * (gv + gv.transpose());
  }
  const Mat3 p = -e.volume_m3 * (r * linear_stress(e, eps));
  for (std::size_t a = 0; a < 4; ++a) out[a] = p * e.grad[a];
  return energy;
}

void corotational_forces(const TetMesh& mesh, const FemElements& el, std::span<const Mat3> rot,
                         std::span<Vec3> f) {
  for (Vec3& fi : f) fi.setZero();
  std::array<Vec3, 4> fe;
  for (std::int32_t t = 0; t < mesh.num_tets(); ++t) {
    const auto ut = static_cast<std::size_t>(t);
    if (!el.elements[ut].active()) continue;
    element_forces(el.elements[ut], rot[ut], mesh.tets[ut], mesh.x, mesh.v, 0.0, fe);
    for (std::size_t a = 0; a < 4; ++a) f[static_cast<std::size_t>(mesh.tets[ut][a])] += fe[a];
  }
}

void linear_forces(const TetMesh& mesh, const FemElements& el, std::span<Vec3> f) {
  const std::vector<Mat3> eye(static_cast<std::size_t>(mesh.num_tets()), Mat3::Identity());
  corotational_forces(mesh, el, eye, f);
}

}  // namespace serosa::fem
