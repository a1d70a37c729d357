#include "engine/tissue_stress.h"

#include <algorithm>
#include <cmath>

namespace serosa {
namespace {

struct TetKinematics {
  Mat3 f;       // deformation gradient
  Mat3 dm_inv;  // inverse rest edge matrix
  double v0 = 0.0;
  bool ok = false;
};

// A rest edge matrix with this determinant can be inverted (0 for a flat tet, NaN for a broken
// one).
bool invertible(double det) { return std::abs(det) > 0.0 && std::isfinite(det); }

Mat3 rest_edges(const TetMesh& mesh, const Tet& tet) {
  Mat3 dm;
  const Vec3& r0 = mesh.rest[static_cast<std::size_t>(tet[0])];
  for (int k = 1; k < 4; ++k)
    dm.col(k - 1) = mesh.rest[static_cast<std::size_t>(tet[static_cast<std::size_t>(k)])] - r0;
  return dm;
}

// F = Ds Dm^-1 for the current positions.
Mat3 deformation_gradient(const TetMesh& mesh, const Tet& tet, const Mat3& dm_inv) {
  Mat3 ds;
  const Vec3& x0 = mesh.x[static_cast<std::size_t>(tet[0])];
  for (int k = 1; k < 4; ++k)
    ds.col(k - 1) = mesh.x[static_cast<std::size_t>(tet[static_cast<std::size_t>(k)])] - x0;
  return ds * dm_inv;
}

TetKinematics kinematics(const TetMesh& mesh, std::int32_t t) {
  const Tet& tet = mesh.tets[static_cast<std::size_t>(t)];
  const Mat3 dm = rest_edges(mesh, tet);
  TetKinematics kin;
  const double det = dm.determinant();
  if (!invertible(det)) return kin;
  kin.dm_inv = dm.inverse();
  kin.f = deformation_gradient(mesh, tet, kin.dm_inv);
  kin.v0 = std::abs(det) / 6.0;
  kin.ok = kin.f.allFinite();
  return kin;
}

Mat3 pk2(const Mat3& f, const Lame& l) {
  const Mat3 e = 0.5 * (f.transpose() * f - Mat3::Identity());
  return 2.0 * l.mu * e + l.lambda * e.trace() * Mat3::Identity();
}

double von_mises_of(const Mat3& f, const Lame& lame) {
  const Mat3 s = pk2(f, lame);
  const double a = s(0, 0) - s(1, 1), b = s(1, 1) - s(2, 2), c = s(2, 2) - s(0, 0);
  const double shear = s(0, 1) * s(0, 1) + s(1, 2) * s(1, 2) + s(2, 0) * s(2, 0);
  return std::sqrt(0.5 * (a * a + b * b + c * c) + 3.0 * shear);
}

}  // namespace

Lame lame(const Material& m) {
  Lame l;
  l.mu = m.young_pa / (2.0 * (1.0 + m.poisson));
  l.lambda = m.young_pa * m.poisson / ((1.0 + m.poisson) * (1.0 - 2.0 * m.poisson));
  return l;
}

double von_mises_pa(const TetMesh& mesh, std::int32_t t, const Lame& lame) {
  const TetKinematics kin = kinematics(mesh, t);
  return kin.ok ? von_mises_of(kin.f, lame) : 0.0;
}

void fill_rest_stress(const TetMesh& mesh, const LameTable& table, RestStress& rest) {
  const auto m = static_cast<std::size_t>(mesh.num_tets());
  rest.dm_inv.assign(m, Mat3::Zero());
  rest.lame.resize(m);
  rest.ok.assign(m, 0);
  for (std::size_t t = 0; t < m; ++t) {
    rest.lame[t] = table.of(mesh.group[t]);
    const Mat3 dm = rest_edges(mesh, mesh.tets[t]);
    const double det = dm.determinant();
    if (!invertible(det)) continue;
    rest.dm_inv[t] = dm.inverse();
    rest.ok[t] = 1;
  }
}

double peak_von_mises_pa(const TetMesh& mesh, const RestStress& rest) {
  double peak = 0.0;
  for (std::size_t t = 0; t < rest.ok.size(); ++t) {
    if (!rest.ok[t]) continue;
    const Mat3 f = deformation_gradient(mesh, mesh.tets[t], rest.dm_inv[t]);
    if (f.allFinite()) peak = std::max(peak, von_mises_of(f, rest.lame[t]));
  }
  return peak;
}

void add_elastic_forces(const TetMesh& mesh, const LameTable& table,
                        std::span<const std::uint8_t> wanted, std::vector<Vec3>& f) {
  for (std::int32_t t = 0; t < mesh.num_tets(); ++t) {
    const Tet& tet = mesh.tets[static_cast<std::size_t>(t)];
    if (std::none_of(tet.begin(), tet.end(),
                     [&](std::int32_t n) { return wanted[static_cast<std::size_t>(n)] != 0; }))
      continue;
    const TetKinematics kin = kinematics(mesh, t);
    if (!kin.ok) continue;
    const Mat3 p = kin.f * pk2(kin.f, table.of(mesh.group[static_cast<std::size_t>(t)]));
    const Mat3 h = -kin.v0 * p * kin.dm_inv.transpose();  // columns: forces on nodes 1..3
    Vec3 f0 = Vec3::Zero();
    for (int k = 1; k < 4; ++k) {
      f[static_cast<std::size_t>(tet[static_cast<std::size_t>(k)])] += h.col(k - 1);
      f0 -= h.col(k - 1);
    }
    f[static_cast<std::size_t>(tet[0])] += f0;
  }
}

}  // namespace serosa
