#include "cutting/remove_cut.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <vector>

#include "engine/geometry/tet_extent.h"

namespace serosa::cutting {
namespace {

using V2 = Eigen::Vector2d;

// True when some axis among the edge normals of `blade2` and the directions between pairs of
// `sec` separates the two point sets by more than tol. Every such axis is a genuine separating
// direction; together they include both convex outlines' edge normals, so the test is exact.
bool overlap_2d(const std::vector<V2>& blade2, const std::array<V2, 4>& sec, int ns, double tol) {
  auto separated = [&](const V2& axis) {
    const double len = axis.norm();
    if (!(len > 0.0)) return false;
    const V2 a = axis / len;
    double blo = a.dot(blade2[0]), bhi = blo;
    for (const V2& p : blade2) {
      blo = std::min(blo, a.dot(p));
      bhi = std::max(bhi, a.dot(p));
    }
    double slo = a.dot(sec[0]), shi = slo;
    for (int k = 1; k < ns; ++k) {
      slo = std::min(slo, a.dot(sec[static_cast<std::size_t>(k)]));
      shi = std::max(shi, a.dot(sec[static_cast<std::size_t>(k)]));
    }
    return shi < blo - tol || slo > bhi + tol;
  };
  const std::size_t k = blade2.size();
  for (std::size_t i = 0; i < k; ++i) {
    const V2 e = blade2[(i + 1) % k] - blade2[i];
    if (separated(V2(-e.y(), e.x()))) return false;
  }
  for (int i = 0; i < ns; ++i)
    for (int j = i + 1; j < ns; ++j) {
      const V2 e = sec[static_cast<std::size_t>(j)] - sec[static_cast<std::size_t>(i)];
      if (separated(V2(-e.y(), e.x()))) return false;
    }
  return true;
}

bool touches(const std::array<Vec3, 4>& p, const ConvexPolygon& blade,
             const std::vector<V2>& blade2, double tol) {
  std::array<double, 4> phi{};
  bool pos = false, neg = false;
  for (std::size_t k = 0; k < 4; ++k) {
    phi[k] = blade.signed_distance(p[k]);
    pos = pos || phi[k] >= -tol;
    neg = neg || phi[k] <= tol;
  }
  if (!pos || !neg) return false;  // all strictly on one side
  // The section: nodes on the plane and the crossing points of edges with opposite signs.
  std::array<V2, 4> sec{};
  int ns = 0;
  for (std::size_t k = 0; k < 4; ++k)
    if (std::abs(phi[k]) <= tol) sec[static_cast<std::size_t>(ns++)] = blade.to_plane(p[k]);
  for (std::size_t i = 0; i < 4; ++i)
    for (std::size_t j = i + 1; j < 4; ++j) {
      const bool cross = (phi[i] > tol && phi[j] < -tol) || (phi[i] < -tol && phi[j] > tol);
      if (!cross || ns >= 4) continue;  // a plane meets at most 4 edges of a tet
      const double t = phi[i] / (phi[i] - phi[j]);
      sec[static_cast<std::size_t>(ns++)] = blade.to_plane(p[i] + t * (p[j] - p[i]));
    }
  if (ns == 0) return false;
  return overlap_2d(blade2, sec, ns, tol);
}

std::vector<V2> plane_points(const ConvexPolygon& blade) {
  std::vector<V2> out;
  out.reserve(blade.size());
  for (const Vec3& p : blade.points()) out.push_back(blade.to_plane(p));
  return out;
}

}  // namespace

bool tet_touches_polygon(const Vec3& a, const Vec3& b, const Vec3& c, const Vec3& d,
                         const ConvexPolygon& blade, double tol) {
  return touches({a, b, c, d}, blade, plane_points(blade), tol);
}

CutResult remove_cut(const TetMesh& mesh, const ConvexPolygon& blade, const CutOptions& options,
                     const TetBoxQuery& query) {
  CutResult result;
  const TetBoxQuery q = query ? query : brute_force_query(mesh);
  // Candidates: boxes meeting the blade's box, then grown by twice the tolerance (as cut_mesh).
  std::vector<std::int32_t> first;
  q(blade.box_min(), blade.box_max(), first);
  if (first.empty()) return result;
  const double h = geometry::longest_edge_m(mesh, first);
  const double tol = options.classify_rel * h;
  result.stats.tolerance_m = tol;
  std::vector<std::int32_t> cands;
  const Vec3 grow = Vec3::Constant(2.0 * tol);
  q(blade.box_min() - grow, blade.box_max() + grow, cands);
  std::sort(cands.begin(), cands.end());
  cands.erase(std::unique(cands.begin(), cands.end()), cands.end());
  result.stats.candidates = static_cast<std::int64_t>(cands.size());

  // The exact test on each candidate; removed ids come out sorted as the delta wants them.
  const std::vector<V2> blade2 = plane_points(blade);
  for (std::int32_t ti : cands) {
    const Tet& t = mesh.tets[static_cast<std::size_t>(ti)];
    if (touches({mesh.x[t[0]], mesh.x[t[1]], mesh.x[t[2]], mesh.x[t[3]]}, blade, blade2, tol))
      result.delta.removed_tets.push_back(ti);
  }
  result.stats.tets_removed = static_cast<std::int64_t>(result.delta.removed_tets.size());
  return result;
}

}  // namespace serosa::cutting
