#include "engine/kuhn_grid.h"

#include <array>
#include <cmath>
#include <stdexcept>
#include <string>
#include <utility>

namespace serosa {
namespace {

void check_axis(const std::vector<double>& c, const char* name) {
  bool ok = c.size() >= 2;
  for (std::size_t i = 0; ok && i < c.size(); ++i)
    ok = std::isfinite(c[i]) && (i == 0 || c[i] > c[i - 1]);
  if (!ok)
    throw std::invalid_argument(std::string("kuhn_grid: ") + name +
                                " needs at least 2 finite, strictly increasing coordinates");
}

}  // namespace

TetMesh kuhn_grid(const KuhnGridSpec& spec) {
  check_axis(spec.xs, "xs");
  check_axis(spec.ys, "ys");
  check_axis(spec.zs, "zs");
  const int nx = static_cast<int>(spec.xs.size()) - 1, ny = static_cast<int>(spec.ys.size()) - 1,
            nz = static_cast<int>(spec.zs.size()) - 1;
  const bool z_fastest = spec.order == KuhnOrder::kZFastest;
  const auto id = [&](int i, int j, int k) {
    return z_fastest ? (i * (ny + 1) + j) * (nz + 1) + k : i + (nx + 1) * (j + (ny + 1) * k);
  };
  TetMesh m;
  m.rest.reserve(spec.xs.size() * spec.ys.size() * spec.zs.size());
  const auto add_node = [&](int i, int j, int k) {
    m.add_node(Vec3(spec.xs[static_cast<std::size_t>(i)], spec.ys[static_cast<std::size_t>(j)],
                    spec.zs[static_cast<std::size_t>(k)]));
  };
  constexpr int kPerms[6][3] = {{0, 1, 2}, {0, 2, 1}, {1, 0, 2}, {1, 2, 0}, {2, 0, 1}, {2, 1, 0}};
  const auto add_cell = [&](int i, int j, int k) {
    const std::uint16_t group = spec.group ? spec.group(i, j, k) : std::uint16_t{1};
    for (const auto& p : kPerms) {
      std::array<int, 3> c{i, j, k};
      Tet t{};
      t[0] = id(c[0], c[1], c[2]);
      for (std::size_t s = 0; s < 3; ++s) {
        ++c[static_cast<std::size_t>(p[s])];
        t[s + 1] = id(c[0], c[1], c[2]);
      }
      const int tet = m.add_tet(t, group);
      if (m.rest_volume(tet) < 0.0) std::swap(m.tets.back()[2], m.tets.back()[3]);
    }
  };
  m.tets.reserve(static_cast<std::size_t>(6 * nx * ny * nz));
  m.group.reserve(m.tets.capacity());
  // Nodes in id order; cells in the same order.
  if (z_fastest) {
    for (int i = 0; i <= nx; ++i)
      for (int j = 0; j <= ny; ++j)
        for (int k = 0; k <= nz; ++k) add_node(i, j, k);
    for (int i = 0; i < nx; ++i)
      for (int j = 0; j < ny; ++j)
        for (int k = 0; k < nz; ++k) add_cell(i, j, k);
  } else {
    for (int k = 0; k <= nz; ++k)
      for (int j = 0; j <= ny; ++j)
        for (int i = 0; i <= nx; ++i) add_node(i, j, k);
    for (int k = 0; k < nz; ++k)
      for (int j = 0; j < ny; ++j)
        for (int i = 0; i < nx; ++i) add_cell(i, j, k);
  }
  return m;
}

std::vector<double> kuhn_axis(int count, double h, double origin) {
  std::vector<double> c;
  for (int i = 0; i <= count; ++i) c.push_back(i * h + origin);
  return c;
}

TetMesh kuhn_grid(int n, double h, bool two_groups) {
  if (n < 1 || !(h > 0.0) || !std::isfinite(h))
    throw std::invalid_argument("kuhn_grid: needs n >= 1 cells and a positive finite edge h");
  KuhnGridSpec spec;
  spec.xs = spec.ys = spec.zs = kuhn_axis(n, h);
  if (two_groups)
    spec.group = [n](int i, int, int) { return static_cast<std::uint16_t>(i >= n / 2 ? 2 : 1); };
  return kuhn_grid(spec);
}

}  // namespace serosa
