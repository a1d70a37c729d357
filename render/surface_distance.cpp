#include "render/surface_distance.h"

#include <algorithm>
#include <cmath>
#include <map>
#include <utility>

#include "engine/geometry/point_triangle.h"
#include "engine/tet_faces.h"

namespace serosa::render {
namespace {

using V3 = std::array<double, 3>;

Vec3 vec(const V3& p) { return {p[0], p[1], p[2]}; }

}  // namespace

TriMesh rest_boundary(const TetMesh& m) {
  std::map<std::array<std::int32_t, 3>, std::pair<int, std::array<std::int32_t, 4>>> faces;
  for (const Tet& t : m.tets)
    for (int k = 0; k < 4; ++k) {
      const Tri f = tet_face(t, k);  // the face opposite local node k
      std::array<std::int32_t, 3> key = f;
      std::sort(key.begin(), key.end());
      auto& e = faces[key];
      ++e.first;
      e.second = {f[0], f[1], f[2], t[static_cast<std::size_t>(k)]};
    }
  TriMesh out;
  for (const Vec3& p : m.rest)
    for (int k = 0; k < 3; ++k) out.pos.push_back(static_cast<float>(p[k]));
  const auto at = [&m](std::int32_t i) -> const Vec3& {
    return m.rest[static_cast<std::size_t>(i)];
  };
  for (const auto& [key, e] : faces) {
    if (e.first != 1) continue;
    auto [a, b, c, d] = e.second;
    const Vec3 n = (at(b) - at(a)).cross(at(c) - at(a));
    if (n.dot(at(d) - at(a)) > 0.0) std::swap(b, c);
    for (const std::int32_t v : {a, b, c}) out.tri.push_back(static_cast<std::uint32_t>(v));
  }
  return out;
}

SurfaceDistance::SurfaceDistance(const TriMesh& m) : m_(m) {
  const std::size_t t = m.tri.size() / 3;
  lo_ = {1e30, 1e30, 1e30};
  double edge = 0.0;
  for (std::size_t f = 0; f < t; ++f)
    for (std::size_t k = 0; k < 3; ++k) {
      const V3 p = point(m.tri[3 * f + k]);
      const V3 q = point(m.tri[3 * f + (k + 1) % 3]);
      edge += (vec(p) - vec(q)).norm();
      for (std::size_t d = 0; d < 3; ++d) lo_[d] = std::min(lo_[d], p[d]);
    }
  cell_ = 2.0 * edge / static_cast<double>(3 * std::max<std::size_t>(t, 1));
  if (!(cell_ > 0.0)) cell_ = 1.0;
  for (std::size_t f = 0; f < t; ++f) {
    std::array<std::int64_t, 3> a{}, b{};
    for (std::size_t d = 0; d < 3; ++d) {
      double mn = 1e30, mx = -1e30;
      for (std::size_t k = 0; k < 3; ++k) {
        const double c = point(m.tri[3 * f + k])[d];
        mn = std::min(mn, c);
        mx = std::max(mx, c);
      }
      a[d] = cell_of(mn, static_cast<int>(d));
      b[d] = cell_of(mx, static_cast<int>(d));
    }
    for (std::int64_t i = a[0]; i <= b[0]; ++i)
      for (std::int64_t j = a[1]; j <= b[1]; ++j)
        for (std::int64_t k = a[2]; k <= b[2]; ++k)
          grid_[key(i, j, k)].push_back(static_cast<std::uint32_t>(f));
  }
}

double SurfaceDistance::operator()(const V3& p) const {
  const std::array<std::int64_t, 3> c{cell_of(p[0], 0), cell_of(p[1], 1), cell_of(p[2], 2)};
  double best = 1e300;
  for (std::int64_t r = 0; r < 64; ++r) {
    for (std::int64_t i = -r; i <= r; ++i)
      for (std::int64_t j = -r; j <= r; ++j)
        for (std::int64_t k = -r; k <= r; ++k) {
          if (std::max({std::abs(i), std::abs(j), std::abs(k)}) != r) continue;  // the shell
          const auto it = grid_.find(key(c[0] + i, c[1] + j, c[2] + k));
          if (it == grid_.end()) continue;
          for (const std::uint32_t f : it->second)
            best = std::min(best, geometry::closest_point_on_triangle(
                                      vec(p), vec(point(m_.tri[3 * f])),
                                      vec(point(m_.tri[3 * f + 1])), vec(point(m_.tri[3 * f + 2])))
                                      .dist2);
        }
    // Cells beyond shell r are at least r * cell away.
    if (best < 1e300 && std::sqrt(best) <= static_cast<double>(r) * cell_) break;
  }
  return std::sqrt(best);
}

V3 SurfaceDistance::point(std::uint32_t v) const {
  return {static_cast<double>(m_.pos[3 * v]), static_cast<double>(m_.pos[3 * v + 1]),
          static_cast<double>(m_.pos[3 * v + 2])};
}

std::int64_t SurfaceDistance::cell_of(double x, int d) const {
  return static_cast<std::int64_t>(std::floor((x - lo_[static_cast<std::size_t>(d)]) / cell_));
}

std::int64_t SurfaceDistance::key(std::int64_t i, std::int64_t j, std::int64_t k) {
  return ((i + 4096) << 42) | ((j + 4096) << 21) | (k + 4096);
}

MeshDistance mesh_distance(const TriMesh& m, const SurfaceDistance& reference) {
  double max_d = 0.0, sum_d = 0.0;
  std::size_t n = 0;
  auto sample = [&](const V3& p) {
    const double d = reference(p);
    max_d = std::max(max_d, d);
    sum_d += d;
    ++n;
  };
  for (std::size_t v = 0; v < m.pos.size() / 3; ++v)
    sample({static_cast<double>(m.pos[3 * v]), static_cast<double>(m.pos[3 * v + 1]),
            static_cast<double>(m.pos[3 * v + 2])});
  for (std::size_t f = 0; f < m.tri.size() / 3; ++f) {
    V3 c{};
    for (std::size_t k = 0; k < 3; ++k)
      for (std::size_t d = 0; d < 3; ++d)
        c[d] += static_cast<double>(m.pos[3 * m.tri[3 * f + k] + d]) / 3.0;
    sample(c);
  }
  MeshDistance out;
  out.max_m = max_d;
  out.mean_m = sum_d / static_cast<double>(std::max<std::size_t>(n, 1));
  return out;
}

}  // namespace serosa::render
