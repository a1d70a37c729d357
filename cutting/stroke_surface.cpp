#include "cutting/stroke_surface.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>

namespace serosa::cutting {
namespace {

double orient(const Vec2& a, const Vec2& b, const Vec2& c) {
  return (b.x() - a.x()) * (c.y() - a.y()) - (b.y() - a.y()) * (c.x() - a.x());
}

// d strictly inside the circle through the counter-clockwise a, b, c.
bool in_circle(const Vec2& a, const Vec2& b, const Vec2& c, const Vec2& d) {
  const Vec2 ad = a - d, bd = b - d, cd = c - d;
  const double det = ad.squaredNorm() * (bd.x() * cd.y() - cd.x() * bd.y()) -
                     bd.squaredNorm() * (ad.x() * cd.y() - cd.x() * ad.y()) +
                     cd.squaredNorm() * (ad.x() * bd.y() - bd.x() * ad.y());
  return det > 0.0;
}

std::uint64_t edge_id(int a, int b) {
  const auto lo = static_cast<std::uint32_t>(std::min(a, b));
  const auto hi = static_cast<std::uint32_t>(std::max(a, b));
  return (static_cast<std::uint64_t>(lo) << 32) | hi;
}

// Edges of `tris` used by exactly one of them, oriented as in their triangle.
std::vector<std::array<int, 2>> lone_edges(const std::vector<std::array<int, 3>>& tris) {
  std::vector<std::pair<std::uint64_t, std::array<int, 2>>> all;
  for (const auto& t : tris)
    for (int k = 0; k < 3; ++k) {
      const int a = t[static_cast<std::size_t>(k)], b = t[static_cast<std::size_t>((k + 1) % 3)];
      all.push_back({edge_id(a, b), {a, b}});
    }
  std::sort(all.begin(), all.end(), [](const auto& x, const auto& y) { return x.first < y.first; });
  std::vector<std::array<int, 2>> out;
  for (std::size_t i = 0; i < all.size();) {
    std::size_t j = i;
    while (j < all.size() && all[j].first == all[i].first) ++j;
    if (j - i == 1) out.push_back(all[i].second);
    i = j;
  }
  return out;
}

// |grad h| of the linear function through (q_i, h_i); 0 for a sliver (its gradient says nothing
// about the surface: the points are nearly collinear).
double slope(const Vec2& a, const Vec2& b, const Vec2& c, double ha, double hb, double hc) {
  const double area2 = orient(a, b, c);
  const double longest =
      std::max({(b - a).squaredNorm(), (c - b).squaredNorm(), (a - c).squaredNorm()});
  if (!(std::abs(area2) > 1e-3 * longest)) return 0.0;
  const Vec2 e1 = b - a, e2 = c - a;
  const double d1 = hb - ha, d2 = hc - ha;
  const Vec2 g((d1 * e2.y() - d2 * e1.y()) / area2, (e1.x() * d2 - e2.x() * d1) / area2);
  return g.norm();
}

}  // namespace

std::vector<std::array<int, 3>> delaunay2d(const std::vector<Vec2>& points) {
  const int n = static_cast<int>(points.size());
  if (n < 3) return {};
  Vec2 lo = points[0], hi = points[0];
  for (const Vec2& p : points) {
    lo = lo.cwiseMin(p);
    hi = hi.cwiseMax(p);
  }
  const Vec2 c = 0.5 * (lo + hi);
  const double s = std::max((hi - lo).maxCoeff(), 1e-300);
  std::vector<Vec2> q;  // normalised to about [-0.5, 0.5], then the super triangle's corners
  q.reserve(points.size() + 3);
  for (const Vec2& p : points) q.push_back((p - c) / s);
  q.emplace_back(-1e3, -1e3);
  q.emplace_back(1e3, -1e3);
  q.emplace_back(0.0, 1e3);
  std::vector<std::array<int, 3>> tris{{n, n + 1, n + 2}};
  std::vector<std::array<int, 3>> kept;
  std::vector<std::array<int, 3>> bad;
  for (int i = 0; i < n; ++i) {
    kept.clear();
    bad.clear();
    for (const auto& t : tris)
      (in_circle(q[t[0]], q[t[1]], q[t[2]], q[i]) ? bad : kept).push_back(t);
    if (bad.empty()) continue;  // (a repeated point: already a vertex)
    for (const auto& e : lone_edges(bad))
      if (orient(q[e[0]], q[e[1]], q[i]) > 0.0) kept.push_back({e[0], e[1], i});
    tris.swap(kept);
  }
  std::vector<std::array<int, 3>> out;
  for (const auto& t : tris)
    if (t[0] < n && t[1] < n && t[2] < n) out.push_back(t);
  return out;
}

std::optional<StrokeSurface> StrokeSurface::make(const PlaneFit& fit, std::span<const Vec3> points,
                                                 double merge_m) {
  StrokeSurface s;
  s.m_fit = fit;
  const double merge2 = merge_m * merge_m;
  for (const Vec3& p : points) {
    if (!p.allFinite()) return std::nullopt;
    const Vec2 q = fit.to_plane(p);
    const bool repeated = std::any_of(
        s.m_q.begin(), s.m_q.end(), [&](const Vec2& o) { return (o - q).squaredNorm() <= merge2; });
    if (repeated) continue;
    s.m_q.push_back(q);
    s.m_h.push_back(fit.normal.dot(p - fit.centroid));
  }
  s.m_tris = delaunay2d(s.m_q);
  if (s.m_tris.empty()) return std::nullopt;
  for (double h : s.m_h) s.m_max_abs_h = std::max(s.m_max_abs_h, std::abs(h));
  for (const auto& t : s.m_tris)
    s.m_max_slope = std::max(s.m_max_slope, slope(s.m_q[t[0]], s.m_q[t[1]], s.m_q[t[2]],
                                                  s.m_h[t[0]], s.m_h[t[1]], s.m_h[t[2]]));
  s.m_edges = lone_edges(s.m_tris);
  s.build_bins();
  return s;
}

void StrokeSurface::build_bins() {
  m_lo = m_q[0];
  Vec2 hi = m_q[0];
  for (const Vec2& q : m_q) {
    m_lo = m_lo.cwiseMin(q);
    hi = hi.cwiseMax(q);
  }
  const int per_side =
      std::clamp(static_cast<int>(std::sqrt(static_cast<double>(m_tris.size()))), 1, 64);
  m_cell = std::max((hi - m_lo).maxCoeff() / per_side, 1e-12);
  m_nx = std::clamp(static_cast<int>((hi.x() - m_lo.x()) / m_cell) + 1, 1, 65);
  m_ny = std::clamp(static_cast<int>((hi.y() - m_lo.y()) / m_cell) + 1, 1, 65);
  const auto cell = [&](double v, double lo, int count) {
    return std::clamp(static_cast<int>(std::floor((v - lo) / m_cell)), 0, count - 1);
  };
  std::vector<std::vector<int>> bins(static_cast<std::size_t>(m_nx * m_ny));
  for (std::size_t t = 0; t < m_tris.size(); ++t) {
    Vec2 lo = m_q[m_tris[t][0]], up = lo;
    for (int k : m_tris[t]) {
      lo = lo.cwiseMin(m_q[k]);
      up = up.cwiseMax(m_q[k]);
    }
    for (int i = cell(lo.x(), m_lo.x(), m_nx); i <= cell(up.x(), m_lo.x(), m_nx); ++i)
      for (int j = cell(lo.y(), m_lo.y(), m_ny); j <= cell(up.y(), m_lo.y(), m_ny); ++j)
        bins[static_cast<std::size_t>(j * m_nx + i)].push_back(static_cast<int>(t));
  }
  m_bin_start.assign(1, 0);
  for (const auto& b : bins) {
    m_bin_tris.insert(m_bin_tris.end(), b.begin(), b.end());
    m_bin_start.push_back(static_cast<int>(m_bin_tris.size()));
  }
}

double StrokeSurface::height(const Vec2& q) const {
  const int i = static_cast<int>(std::floor((q.x() - m_lo.x()) / m_cell));
  const int j = static_cast<int>(std::floor((q.y() - m_lo.y()) / m_cell));
  if (i >= 0 && i < m_nx && j >= 0 && j < m_ny) {
    const auto b = static_cast<std::size_t>(j * m_nx + i);
    for (int k = m_bin_start[b]; k < m_bin_start[b + 1]; ++k) {
      const auto& t = m_tris[static_cast<std::size_t>(m_bin_tris[static_cast<std::size_t>(k)])];
      const Vec2 &a = m_q[t[0]], &bq = m_q[t[1]], &c = m_q[t[2]];
      const double area = orient(a, bq, c);
      const double w0 = orient(bq, c, q) / area, w1 = orient(c, a, q) / area;
      const double w2 = 1.0 - w0 - w1;
      const double eps = -1e-12;
      if (w0 >= eps && w1 >= eps && w2 >= eps)
        return w0 * m_h[t[0]] + w1 * m_h[t[1]] + w2 * m_h[t[2]];
    }
  }
  return boundary_height(q);
}

double StrokeSurface::boundary_height(const Vec2& q) const {
  double best = std::numeric_limits<double>::infinity(), h = 0.0;
  for (const auto& e : m_edges) {
    const Vec2 &a = m_q[e[0]], &b = m_q[e[1]];
    const Vec2 d = b - a;
    const double len2 = d.squaredNorm();
    const double t = len2 > 0.0 ? std::clamp((q - a).dot(d) / len2, 0.0, 1.0) : 0.0;
    const double dist = (a + t * d - q).squaredNorm();
    if (dist < best) {
      best = dist;
      h = (1.0 - t) * m_h[e[0]] + t * m_h[e[1]];
    }
  }
  return h;
}

}  // namespace serosa::cutting
