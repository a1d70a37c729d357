#include "cutting/section_triangulation.h"

#include <algorithm>
#include <cmath>

namespace serosa::cutting {
namespace {

using V2 = Eigen::Vector2d;

// Distance from p to segment [a, b].
double segment_distance(const V2& p, const V2& a, const V2& b) {
  const V2 d = b - a;
  const double l2 = d.squaredNorm();
  const double t = l2 > 0.0 ? std::clamp(d.dot(p - a) / l2, 0.0, 1.0) : 0.0;
  return (a + t * d - p).norm();
}

// Side of c against the line a -> b: +1 left, -1 right, 0 within eps of it.
int side(const V2& a, const V2& b, const V2& c, double eps) {
  const double len = (b - a).norm();
  const double cr = (b - a).x() * (c - a).y() - (b - a).y() * (c - a).x();
  if (cr > eps * len) return 1;
  if (cr < -eps * len) return -1;
  return 0;
}

}  // namespace

std::vector<std::array<int, 3>> triangulate_section(std::span<const V2> points,
                                                    std::span<const std::array<int, 2>> constraints,
                                                    double eps) {
  const int n = static_cast<int>(points.size());
  std::vector<char> edge(static_cast<std::size_t>(n * n), 0);
  std::vector<std::array<int, 2>> kept;
  auto crosses = [&](int a, int b, int c, int d) {
    if (a == c || a == d || b == c || b == d) return false;
    const V2 &pa = points[a], &pb = points[b], &pc = points[c], &pd = points[d];
    return side(pa, pb, pc, eps) * side(pa, pb, pd, eps) < 0 &&
           side(pc, pd, pa, eps) * side(pc, pd, pb, eps) < 0;
  };
  auto keep = [&](int a, int b) {
    kept.push_back({a, b});
    edge[static_cast<std::size_t>(a * n + b)] = edge[static_cast<std::size_t>(b * n + a)] = 1;
  };
  for (const auto& c : constraints)
    if (!edge[static_cast<std::size_t>(c[0] * n + c[1])]) keep(c[0], c[1]);
  std::vector<std::pair<double, std::array<int, 2>>> cand;
  for (int a = 0; a < n; ++a)
    for (int b = a + 1; b < n; ++b) {
      if (edge[static_cast<std::size_t>(a * n + b)]) continue;
      bool through = false;
      for (int k = 0; k < n && !through; ++k)
        through = k != a && k != b && segment_distance(points[k], points[a], points[b]) <= eps;
      if (!through) cand.push_back({(points[a] - points[b]).squaredNorm(), {a, b}});
    }
  std::sort(cand.begin(), cand.end());
  for (const auto& [len2, s] : cand) {
    bool ok = true;
    for (const auto& k : kept) ok = ok && !crosses(s[0], s[1], k[0], k[1]);
    if (ok) keep(s[0], s[1]);
  }
  std::vector<std::array<int, 3>> tris;
  auto has = [&](int a, int b) { return edge[static_cast<std::size_t>(a * n + b)] != 0; };
  for (int a = 0; a < n; ++a)
    for (int b = a + 1; b < n; ++b) {
      if (!has(a, b)) continue;
      for (int c = b + 1; c < n; ++c) {
        if (!has(a, c) || !has(b, c)) continue;
        const int s = side(points[a], points[b], points[c], eps);
        if (s == 0) continue;
        bool empty = true;
        for (int k = 0; k < n && empty; ++k) {
          if (k == a || k == b || k == c) continue;
          const int s1 = side(points[a], points[b], points[k], eps);
          const int s2 = side(points[b], points[c], points[k], eps);
          const int s3 = side(points[c], points[a], points[k], eps);
          empty = !(s1 != -s && s2 != -s && s3 != -s);  // inside or on the boundary
        }
        if (!empty) continue;
        if (s > 0)
          tris.push_back({a, b, c});
        else
          tris.push_back({a, c, b});
      }
    }
  return tris;
}

}  // namespace serosa::cutting
