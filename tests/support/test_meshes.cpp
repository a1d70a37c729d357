#include "support/test_meshes.h"

#include <utility>

#include "engine/kuhn_grid.h"

namespace serosa::test_meshes {

TetMesh kuhn_box(int nx, int ny, int nz, int groups, double h) {
  KuhnGridSpec spec;
  spec.xs = kuhn_axis(nx, h);
  spec.ys = kuhn_axis(ny, h);
  spec.zs = kuhn_axis(nz, h);
  spec.group = [nx, groups](int i, int, int) {
    return static_cast<std::uint16_t>(1 + groups * i / nx);
  };
  return kuhn_grid(spec);
}

TetMesh kuhn_cube(int k, double h, double jitter, std::uint32_t seed) {
  TetMesh m = kuhn_box(k, k, k, 2, h);
  if (!(jitter > 0.0)) return m;
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> u(-jitter * h, jitter * h);
  const double top = k * h;  // the grid's last coordinate, exactly
  for (std::size_t n = 0; n < m.rest.size(); ++n) {
    Vec3& p = m.rest[n];
    const bool interior =
        p.x() > 0.0 && p.x() < top && p.y() > 0.0 && p.y() < top && p.z() > 0.0 && p.z() < top;
    if (interior) p += Vec3(u(rng), u(rng), u(rng));
    m.x[n] = p;
  }
  for (std::int32_t t = 0; t < m.num_tets(); ++t)
    if (m.rest_volume(t) < 0.0) std::swap(m.tets[t][2], m.tets[t][3]);
  return m;
}

TetMesh kuhn_lattice(const std::vector<double>& xs, const std::vector<double>& ys,
                     const std::vector<double>& zs, int groups) {
  KuhnGridSpec spec{xs, ys, zs, KuhnOrder::kXFastest, {}};
  spec.group = [groups](int i, int, int) { return static_cast<std::uint16_t>(1 + i % groups); };
  return kuhn_grid(spec);
}

TetMesh kuhn_bar(int nx, int ny, int nz, double hx, double hy, double hz) {
  return kuhn_lattice(kuhn_axis(nx, hx), kuhn_axis(ny, hy), kuhn_axis(nz, hz));
}

std::vector<double> random_spacing(std::mt19937& rng, int k, double size) {
  std::uniform_real_distribution<double> u(0.3, 1.0);
  std::vector<double> w(static_cast<std::size_t>(k));
  double sum = 0.0;
  for (double& x : w) sum += (x = u(rng));
  std::vector<double> out{0.0};
  double acc = 0.0;
  for (int i = 0; i < k; ++i) {
    acc += w[static_cast<std::size_t>(i)];
    out.push_back(i + 1 == k ? size : size * acc / sum);
  }
  return out;
}

}  // namespace serosa::test_meshes
