#include "render/icosphere.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <map>
#include <utility>
#include <vector>

namespace serosa::render {

TriMesh icosahedron(float radius) {
  const float p = (1.0f + std::sqrt(5.0f)) / 2.0f;
  const std::array<std::array<float, 3>, 12> v{{{-1, p, 0},
                                                {1, p, 0},
                                                {-1, -p, 0},
                                                {1, -p, 0},
                                                {0, -1, p},
                                                {0, 1, p},
                                                {0, -1, -p},
                                                {0, 1, -p},
                                                {p, 0, -1},
                                                {p, 0, 1},
                                                {-p, 0, -1},
                                                {-p, 0, 1}}};
  TriMesh s;
  for (const auto& q : v) {
    const float len = std::sqrt(q[0] * q[0] + q[1] * q[1] + q[2] * q[2]);
    for (const float c : q) s.pos.push_back(radius * c / len);
  }
  s.tri = {0, 11, 5,  0, 5,  1, 0, 1, 7, 0, 7,  10, 0, 10, 11, 1, 5, 9, 5, 11,
           4, 11, 10, 2, 10, 7, 6, 7, 1, 8, 3,  9,  4, 3,  4,  2, 3, 2, 6, 3,
           6, 8,  3,  8, 9,  4, 9, 5, 2, 4, 11, 6,  2, 10, 8,  6, 7, 9, 8, 1};
  return s;
}

TriMesh icosphere(int levels, float radius) {
  TriMesh s = icosahedron(radius);
  for (int l = 0; l < levels; ++l) {
    std::map<std::pair<std::uint32_t, std::uint32_t>, std::uint32_t> mid;
    const auto midpoint = [&](std::uint32_t a, std::uint32_t b) {
      const auto key = std::minmax(a, b);
      const auto it = mid.find(key);
      if (it != mid.end()) return it->second;
      std::array<float, 3> m{};
      for (std::size_t k = 0; k < 3; ++k) m[k] = 0.5f * (s.pos[3 * a + k] + s.pos[3 * b + k]);
      const float len = std::sqrt(m[0] * m[0] + m[1] * m[1] + m[2] * m[2]);
      const auto id = static_cast<std::uint32_t>(s.pos.size() / 3);
      for (const float c : m) s.pos.push_back(radius * c / len);
      mid.emplace(key, id);
      return id;
    };
    std::vector<std::uint32_t> next;
    for (std::size_t f = 0; f < s.tri.size(); f += 3) {
      const std::uint32_t a = s.tri[f], b = s.tri[f + 1], c = s.tri[f + 2];
      const std::uint32_t ab = midpoint(a, b), bc = midpoint(b, c), ca = midpoint(c, a);
      next.insert(next.end(), {a, ab, ca, b, bc, ab, c, ca, bc, ab, bc, ca});
    }
    s.tri = std::move(next);
  }
  return s;
}

}  // namespace serosa::render
