// Phong tessellation on the CPU (see phong_tessellation.h).
#include "render/phong_tessellation.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

namespace serosa::render {
namespace {

using P3 = std::array<float, 3>;

float dot(const P3& a, const P3& b) { return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]; }

P3 unit_or_zero(const P3& n) {
  const float l = std::sqrt(dot(n, n));
  return l > 1e-12f ? P3{n[0] / l, n[1] / l, n[2] / l} : P3{0.0f, 0.0f, 0.0f};
}

}  // namespace

P3 phong_point(const std::array<P3, 3>& p, const std::array<P3, 3>& n, const P3& b, float alpha) {
  P3 lin{};
  for (int i = 0; i < 3; ++i)
    for (int k = 0; k < 3; ++k) lin[k] += b[i] * p[i][k];
  P3 s{};
  for (int i = 0; i < 3; ++i) {
    const P3 u = unit_or_zero(n[i]);
    const P3 d{lin[0] - p[i][0], lin[1] - p[i][1], lin[2] - p[i][2]};
    const float h = dot(d, u);
    for (int k = 0; k < 3; ++k) s[k] += b[i] * (lin[k] - h * u[k]);
  }
  P3 q{};
  for (int k = 0; k < 3; ++k) q[k] = (1.0f - alpha) * lin[k] + alpha * s[k];
  return q;
}

TriMesh phong_tessellate(std::span<const float> pos, std::span<const float> nrm,
                         std::span<const std::uint32_t> tri, int level, float alpha) {
  if (pos.size() % 3 != 0 || nrm.size() != pos.size() || tri.size() % 3 != 0)
    throw std::invalid_argument("phong_tessellate: pos, nrm must be (n x 3), tri (t x 3)");
  if (level < 1) throw std::invalid_argument("phong_tessellate: level must be >= 1");
  const std::size_t n = pos.size() / 3;
  TriMesh out;
  const auto lv = static_cast<std::uint32_t>(level);
  const std::size_t per = (lv + 1) * (lv + 2) / 2;
  out.pos.reserve(3 * per * (tri.size() / 3));
  out.tri.reserve(3 * lv * lv * (tri.size() / 3));
  for (std::size_t t = 0; t + 2 < tri.size(); t += 3) {
    std::array<P3, 3> p{};
    std::array<P3, 3> nn{};
    for (std::size_t c = 0; c < 3; ++c) {
      const std::uint32_t id = tri[t + c];
      if (id >= n)
        throw std::invalid_argument("phong_tessellate: vertex id " + std::to_string(id) +
                                    " out of range");
      for (std::size_t k = 0; k < 3; ++k) {
        p[c][k] = pos[3 * id + k];
        nn[c][k] = nrm[3 * id + k];
      }
    }
    // Grid point (i, j): b = ((L - i - j) / L, i / L, j / L); row-major index within the patch.
    const auto base = static_cast<std::uint32_t>(out.pos.size() / 3);
    const auto index = [&](std::uint32_t i, std::uint32_t j) {
      // Rows of constant j hold L + 1 - j points.
      std::uint32_t idx = 0;
      for (std::uint32_t r = 0; r < j; ++r) idx += lv + 1 - r;
      return base + idx + i;
    };
    const float inv = 1.0f / static_cast<float>(lv);
    for (std::uint32_t j = 0; j <= lv; ++j) {
      for (std::uint32_t i = 0; i + j <= lv; ++i) {
        const float b1 = static_cast<float>(i) * inv;
        const float b2 = static_cast<float>(j) * inv;
        const P3 q = phong_point(p, nn, {1.0f - b1 - b2, b1, b2}, alpha);
        out.pos.insert(out.pos.end(), q.begin(), q.end());
      }
    }
    for (std::uint32_t j = 0; j < lv; ++j) {
      for (std::uint32_t i = 0; i + j < lv; ++i) {
        out.tri.insert(out.tri.end(), {index(i, j), index(i + 1, j), index(i, j + 1)});
        if (i + j + 1 < lv)
          out.tri.insert(out.tri.end(), {index(i + 1, j), index(i + 1, j + 1), index(i, j + 1)});
      }
    }
  }
  return out;
}

SphereDistance distance_to_sphere(const TriMesh& mesh, double radius) {
  SphereDistance d;
  std::size_t samples = 0;
  const auto sample = [&](double x, double y, double z) {
    const double e = std::abs(std::sqrt(x * x + y * y + z * z) - radius);
    d.max_m = std::max(d.max_m, e);
    d.mean_m += e;
    ++samples;
  };
  for (std::size_t t = 0; t + 2 < mesh.tri.size(); t += 3) {
    std::array<std::array<double, 3>, 3> c{};
    for (std::size_t k = 0; k < 3; ++k)
      for (std::size_t a = 0; a < 3; ++a) c[k][a] = mesh.pos[3 * mesh.tri[t + k] + a];
    for (std::size_t k = 0; k < 3; ++k) {
      sample(c[k][0], c[k][1], c[k][2]);
      const auto& o = c[(k + 1) % 3];
      sample(0.5 * (c[k][0] + o[0]), 0.5 * (c[k][1] + o[1]), 0.5 * (c[k][2] + o[2]));
    }
    sample((c[0][0] + c[1][0] + c[2][0]) / 3.0, (c[0][1] + c[1][1] + c[2][1]) / 3.0,
           (c[0][2] + c[1][2] + c[2][2]) / 3.0);
  }
  if (samples > 0) d.mean_m /= static_cast<double>(samples);
  return d;
}

}  // namespace serosa::render
