// Energies of a FEM state for the fem tests (J): kinetic from the lumped masses, and the
// corotational elastic energy sum_e V_e (mu eps:eps + lambda/2 tr(eps)^2), eps = sym(R^T F) - I
// with R the polar rotation of F (what the elastic forces derive from).
#pragma once

#include <cstddef>

#include "engine/tet_mesh.h"
#include "fem/fem_elements.h"
#include "fem/rotation.h"
#include "fem/tet_element.h"

namespace serosa::fem::fixtures {

inline double elastic_energy(const TetMesh& m, const FemElements& el) {
  double e = 0.0;
  for (std::size_t t = 0; t < m.tets.size(); ++t) {
    const TetElement& te = el.elements[t];
    if (!te.active()) continue;
    const Tet& n = m.tets[t];
    const Mat3 f = nodal_gradient(te, m.x[n[0]], m.x[n[1]], m.x[n[2]], m.x[n[3]]);
    const Mat3 rf = polar_rotation_svd(f).transpose() * f;
    const Mat3 eps = 0.5 * (rf + rf.transpose()) - Mat3::Identity();
    e += te.volume_m3 *
         (te.mu_pa * eps.squaredNorm() + 0.5 * te.lambda_pa * eps.trace() * eps.trace());
  }
  return e;
}

inline double kinetic_energy(const TetMesh& m) {
  double e = 0.0;
  for (std::size_t i = 0; i < m.x.size(); ++i) e += 0.5 * m.mass[i] * m.v[i].squaredNorm();
  return e;
}

}  // namespace serosa::fem::fixtures
