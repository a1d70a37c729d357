#include "engine/kuhn_grid.h"

#include <array>
#include <cmath>
#include <stdexcept>
#include <utility>

namespace serosa {

TetMesh kuhn_grid(int n, double h, bool two_groups) {
  if (n < 1 || !(h > 0.0) || !std::isfinite(h))
    throw std::invalid_argument("kuhn_grid: needs n >= 1 cells and a positive finite edge h");
  TetMesh m;
  const auto id = [n](int i, int j, int k) { return (i * (n + 1) + j) * (n + 1) + k; };
  m.rest.reserve(static_cast<std::size_t>((n + 1) * (n + 1) * (n + 1)));
  for (int i = 0; i <= n; ++i)
    for (int j = 0; j <= n; ++j)
      for (int k = 0; k <= n; ++k) m.add_node(Vec3(i * h, j * h, k * h));
  constexpr int kPerms[6][3] = {{0, 1, 2}, {0, 2, 1}, {1, 0, 2}, {1, 2, 0}, {2, 0, 1}, {2, 1, 0}};
  m.tets.reserve(static_cast<std::size_t>(6 * n * n * n));
  m.group.reserve(m.tets.capacity());
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < n; ++j)
      for (int k = 0; k < n; ++k)
        for (const auto& p : kPerms) {
          std::array<int, 3> c{i, j, k};
          Tet t{};
          t[0] = id(c[0], c[1], c[2]);
          for (std::size_t s = 0; s < 3; ++s) {
            ++c[static_cast<std::size_t>(p[s])];
            t[s + 1] = id(c[0], c[1], c[2]);
          }
          const auto group = static_cast<std::uint16_t>(two_groups && i >= n / 2 ? 2 : 1);
          const int tet = m.add_tet(t, group);
          if (m.rest_volume(tet) < 0.0) std::swap(m.tets.back()[2], m.tets.back()[3]);
        }
  return m;
}

}  // namespace serosa
