// Area-weighted vertex normals (see vertex_normals.h).
#include "render/vertex_normals.h"

#include <array>
#include <cmath>
#include <stdexcept>
#include <string>

namespace serosa::render {

std::vector<float> compute_vertex_normals(std::span<const float> pos,
                                          std::span<const std::uint32_t> tri) {
  if (pos.size() % 3 != 0 || tri.size() % 3 != 0) {
    throw std::invalid_argument("compute_vertex_normals: pos and tri sizes must be multiples of 3");
  }
  const std::size_t n = pos.size() / 3;
  // Accumulate in double: many small triangles around a vertex would lose bits in float.
  std::vector<double> acc(pos.size(), 0.0);
  for (std::size_t f = 0; f < tri.size(); f += 3) {
    const std::array<std::uint32_t, 3> v{tri[f], tri[f + 1], tri[f + 2]};
    for (const std::uint32_t id : v) {
      if (id >= n) {
        throw std::invalid_argument("compute_vertex_normals: triangle " + std::to_string(f / 3) +
                                    " uses vertex " + std::to_string(id) + " of " +
                                    std::to_string(n));
      }
    }
    std::array<double, 3> e1{};
    std::array<double, 3> e2{};
    for (int k = 0; k < 3; ++k) {
      const double a = pos[3 * v[0] + k];
      e1[k] = static_cast<double>(pos[3 * v[1] + k]) - a;
      e2[k] = static_cast<double>(pos[3 * v[2] + k]) - a;
    }
    // (b - a) x (c - a): length is twice the area, so the sum is area-weighted.
    const std::array<double, 3> c{e1[1] * e2[2] - e1[2] * e2[1], e1[2] * e2[0] - e1[0] * e2[2],
                                  e1[0] * e2[1] - e1[1] * e2[0]};
    for (const std::uint32_t id : v) {
      for (int k = 0; k < 3; ++k) acc[3 * id + k] += c[k];
    }
  }
  std::vector<float> nrm(pos.size(), 0.0f);
  for (std::size_t i = 0; i < n; ++i) {
    const double len = std::sqrt(acc[3 * i] * acc[3 * i] + acc[3 * i + 1] * acc[3 * i + 1] +
                                 acc[3 * i + 2] * acc[3 * i + 2]);
    if (len > 0.0) {
      for (int k = 0; k < 3; ++k) nrm[3 * i + k] = static_cast<float>(acc[3 * i + k] / len);
    }
  }
  return nrm;
}

}  // namespace serosa::render
