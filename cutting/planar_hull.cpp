#include "cutting/planar_hull.h"

#include <Eigen/Eigenvalues>
#include <algorithm>
#include <cmath>

namespace serosa::cutting {
namespace {

double cross2(const Vec2& o, const Vec2& a, const Vec2& b) {
  return (a - o).x() * (b - o).y() - (a - o).y() * (b - o).x();
}

}  // namespace

std::optional<PlaneFit> fit_plane(std::span<const Vec3> points, const Vec3& towards,
                                  double min_width_rel) {
  if (points.size() < 3) return std::nullopt;
  Vec3 c = Vec3::Zero();
  for (const Vec3& p : points) {
    if (!p.allFinite()) return std::nullopt;
    c += p;
  }
  c /= static_cast<double>(points.size());
  Mat3 cov = Mat3::Zero();
  for (const Vec3& p : points) cov += (p - c) * (p - c).transpose();
  const Eigen::SelfAdjointEigenSolver<Mat3> eig(cov);  // eigenvalues ascending
  const Vec3 ev = eig.eigenvalues();
  if (!(ev(1) > min_width_rel * min_width_rel * ev(2)) || !(ev(2) > 0.0)) return std::nullopt;
  PlaneFit f;
  f.centroid = c;
  f.normal = eig.eigenvectors().col(0).normalized();
  if (f.normal.dot(towards) < 0.0) f.normal = -f.normal;
  f.u = eig.eigenvectors().col(2).normalized();
  f.v = f.normal.cross(f.u);
  for (const Vec3& p : points)
    f.deviation_m = std::max(f.deviation_m, std::abs(f.normal.dot(p - c)));
  return f;
}

std::vector<std::size_t> hull2d(const std::vector<Vec2>& pts) {
  std::vector<std::size_t> idx(pts.size());
  for (std::size_t i = 0; i < idx.size(); ++i) idx[i] = i;
  std::sort(idx.begin(), idx.end(), [&](std::size_t a, std::size_t b) {
    return pts[a].x() < pts[b].x() || (pts[a].x() == pts[b].x() && pts[a].y() < pts[b].y());
  });
  if (idx.size() < 3) return idx;
  std::vector<std::size_t> h(2 * idx.size());
  std::size_t k = 0;
  for (std::size_t i : idx) {  // lower hull
    while (k >= 2 && cross2(pts[h[k - 2]], pts[h[k - 1]], pts[i]) <= 0.0) --k;
    h[k++] = i;
  }
  for (std::size_t j = idx.size() - 1, t = k + 1; j-- > 0;) {  // upper hull
    const std::size_t i = idx[j];
    while (k >= t && cross2(pts[h[k - 2]], pts[h[k - 1]], pts[i]) <= 0.0) --k;
    h[k++] = i;
  }
  h.resize(k > 1 ? k - 1 : k);
  return h;
}

std::vector<Vec2> clip_halfplane(const std::vector<Vec2>& poly, const Vec2& at, const Vec2& n) {
  std::vector<Vec2> out;
  const std::size_t m = poly.size();
  for (std::size_t i = 0; i < m; ++i) {
    const Vec2& a = poly[i];
    const Vec2& b = poly[(i + 1) % m];
    const double da = n.dot(a - at), db = n.dot(b - at);
    if (da >= 0.0) out.push_back(a);
    if ((da > 0.0 && db < 0.0) || (da < 0.0 && db > 0.0))
      out.push_back(a + (da / (da - db)) * (b - a));
  }
  return out;
}

std::vector<Vec2> clip_convex(std::vector<Vec2> subject, const std::vector<Vec2>& clip) {
  for (std::size_t i = 0; i < clip.size() && subject.size() >= 3; ++i) {
    const Vec2 e = clip[(i + 1) % clip.size()] - clip[i];
    subject = clip_halfplane(subject, clip[i], Vec2(-e.y(), e.x()));
  }
  return subject;
}

double signed_area(const std::vector<Vec2>& poly) {
  double a = 0.0;
  for (std::size_t i = 0; i < poly.size(); ++i) {
    const Vec2& p = poly[i];
    const Vec2& q = poly[(i + 1) % poly.size()];
    a += p.x() * q.y() - p.y() * q.x();
  }
  return 0.5 * a;
}

}  // namespace serosa::cutting
