#include "cutting/cut_accuracy.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <set>
#include <vector>

#include "engine/boundary.h"
#include "engine/geometry/point_triangle.h"
#include "engine/mesh_quality.h"

namespace serosa::cutting {
namespace {

double total_rest_volume(const TetMesh& m) {
  double v = 0.0;
  for (std::int32_t i = 0; i < m.num_tets(); ++i) v += m.rest_volume(i);
  return v;
}

}  // namespace

double polygon_distance(const ConvexPolygon& blade, const Vec3& p) {
  if (blade.contains_projection(p)) return std::abs(blade.signed_distance(p));
  double best = std::numeric_limits<double>::infinity();
  const auto& q = blade.points();
  for (std::size_t i = 0; i < q.size(); ++i) {
    const Vec3 c = geometry::closest_point_on_segment(p, q[i], q[(i + 1) % q.size()]);
    best = std::min(best, (c - p).norm());
  }
  return best;
}

CutAccuracy measure_cut(const TetMesh& before, const TetMesh& after, const ConvexPolygon& blade,
                        double h) {
  CutAccuracy a;
  a.volume_before_m3 = total_rest_volume(before);
  a.volume_lost_m3 = a.volume_before_m3 - total_rest_volume(after);
  a.volume_lost_rel = a.volume_before_m3 > 0.0 ? a.volume_lost_m3 / a.volume_before_m3 : 0.0;
  const std::vector<double> q = tet_qualities(after);
  a.min_quality = q.empty() ? 0.0 : *std::min_element(q.begin(), q.end());
  const FaceCensus fb = face_census(before), fa = face_census(after);
  auto key = [](Tri t) {
    std::sort(t.begin(), t.end());
    return t;
  };
  std::set<Tri> old;
  for (const BoundaryFace& f : fb.boundary) old.insert(key(f.nodes));
  // Old boundary faces near the blade (the only ones a new face can lie on).
  const Vec3 lo = blade.box_min() - Vec3::Constant(3.0 * h),
             hi = blade.box_max() + Vec3::Constant(3.0 * h);
  std::vector<Tri> near;
  for (const BoundaryFace& f : fb.boundary) {
    const Vec3& p = before.rest[static_cast<std::size_t>(f.nodes[0])];
    if ((p.array() >= lo.array()).all() && (p.array() <= hi.array()).all()) near.push_back(f.nodes);
  }
  const auto at = [](const TetMesh& m, std::int32_t i) -> const Vec3& {
    return m.rest[static_cast<std::size_t>(i)];
  };
  double weighted = 0.0;
  for (const BoundaryFace& f : fa.boundary) {
    if (old.contains(key(f.nodes))) continue;
    const Vec3 &p0 = at(after, f.nodes[0]), &p1 = at(after, f.nodes[1]),
               &p2 = at(after, f.nodes[2]);
    const Vec3 c = (p0 + p1 + p2) / 3.0;
    bool on_old = false;
    for (const Tri& o : near)
      if (geometry::point_triangle_distance(c, at(before, o[0]), at(before, o[1]),
                                            at(before, o[2])) <= 1e-9 * h) {
        on_old = true;
        break;
      }
    if (on_old) continue;
    const double area = 0.5 * (p1 - p0).cross(p2 - p0).norm();
    double sum = 0.0;
    for (const Vec3* p : {&p0, &p1, &p2}) {
      const double d = polygon_distance(blade, *p);
      sum += d;
      a.max_dist_m = std::max(a.max_dist_m, d);
      a.max_plane_dist_m = std::max(a.max_plane_dist_m, std::abs(blade.signed_distance(*p)));
    }
    weighted += area * sum / 3.0;
    a.cut_area_m2 += area;
    ++a.cut_faces;
  }
  a.mean_dist_m = a.cut_area_m2 > 0.0 ? weighted / a.cut_area_m2 : 0.0;
  return a;
}

}  // namespace serosa::cutting
