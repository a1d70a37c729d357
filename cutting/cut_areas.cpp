#include "cutting/cut_areas.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <vector>

#include "cutting/planar_hull.h"
#include "engine/mesh_quality.h"

namespace serosa::cutting {
namespace {

constexpr std::array<std::array<int, 3>, 4> kFaces{{{1, 2, 3}, {0, 3, 2}, {0, 1, 3}, {0, 2, 1}}};

using Triple = std::array<std::int32_t, 3>;

Triple sorted(std::int32_t a, std::int32_t b, std::int32_t c) {
  Triple t{a, b, c};
  std::sort(t.begin(), t.end());
  return t;
}

// The section of the tet (a, b, c, d) by the polygon's plane, in the polygon's coordinates,
// counter-clockwise; empty when the plane misses it.
std::vector<Vec2> section(const ConvexPolygon& p, const std::array<Vec3, 4>& x) {
  std::array<double, 4> d{};
  for (int i = 0; i < 4; ++i)
    d[static_cast<std::size_t>(i)] = p.signed_distance(x[static_cast<std::size_t>(i)]);
  std::vector<Vec2> pts;
  for (int i = 0; i < 4; ++i) {
    const auto ui = static_cast<std::size_t>(i);
    if (d[ui] == 0.0) pts.push_back(p.to_plane(x[ui]));
    for (int j = i + 1; j < 4; ++j) {
      const auto uj = static_cast<std::size_t>(j);
      if ((d[ui] < 0.0 && d[uj] > 0.0) || (d[ui] > 0.0 && d[uj] < 0.0))
        pts.push_back(p.to_plane(x[ui] + (d[ui] / (d[ui] - d[uj])) * (x[uj] - x[ui])));
    }
  }
  std::vector<Vec2> out;
  for (std::size_t i : hull2d(pts)) out.push_back(pts[i]);
  return out;
}

}  // namespace

double swept_area(const TetMesh& mesh, std::span<const std::int32_t> tets,
                  const ConvexPolygon& polygon) {
  std::vector<Vec2> outline;
  for (const Vec3& v : polygon.points()) outline.push_back(polygon.to_plane(v));
  if (signed_area(outline) < 0.0) std::reverse(outline.begin(), outline.end());
  double area = 0.0;
  for (std::int32_t t : tets) {
    const Tet& tet = mesh.tets[static_cast<std::size_t>(t)];
    std::array<Vec3, 4> x;
    for (std::size_t i = 0; i < 4; ++i) x[i] = mesh.x[static_cast<std::size_t>(tet[i])];
    const std::vector<Vec2> s = clip_convex(section(polygon, x), outline);
    if (s.size() >= 3) area += std::abs(signed_area(s));
  }
  return area;
}

double crack_area(const TetMesh& after, const TopologyDelta& delta, const ConvexPolygon& polygon,
                  double tol_m) {
  const auto on_plane = [&](std::int32_t n) {
    return std::abs(polygon.signed_distance(after.x[static_cast<std::size_t>(n)])) <= tol_m;
  };
  std::vector<Triple> crack;  // faces of added tets on the polygon
  std::vector<char> touched(after.x.size(), 0);
  for (std::int32_t slot : delta.slot_of_added) {
    const Tet& t = after.tets[static_cast<std::size_t>(slot)];
    for (const auto& f : kFaces) {
      const std::int32_t a = t[static_cast<std::size_t>(f[0])],
                         b = t[static_cast<std::size_t>(f[1])],
                         c = t[static_cast<std::size_t>(f[2])];
      if (!on_plane(a) || !on_plane(b) || !on_plane(c)) continue;
      const Vec3 mid =
          (after.x[static_cast<std::size_t>(a)] + after.x[static_cast<std::size_t>(b)] +
           after.x[static_cast<std::size_t>(c)]) /
          3.0;
      if (!polygon.contains_projection(mid, tol_m)) continue;
      crack.push_back(sorted(a, b, c));
      touched[static_cast<std::size_t>(a)] = 1;
    }
  }
  // A crack face is a boundary face: no other tet has it.
  std::vector<Triple> near;
  for (const Tet& t : after.tets) {
    if (!touched[static_cast<std::size_t>(t[0])] && !touched[static_cast<std::size_t>(t[1])] &&
        !touched[static_cast<std::size_t>(t[2])] && !touched[static_cast<std::size_t>(t[3])])
      continue;
    for (const auto& f : kFaces)
      near.push_back(sorted(t[static_cast<std::size_t>(f[0])], t[static_cast<std::size_t>(f[1])],
                            t[static_cast<std::size_t>(f[2])]));
  }
  std::sort(near.begin(), near.end());
  double area = 0.0;
  for (const Triple& f : crack) {
    const auto [lo, hi] = std::equal_range(near.begin(), near.end(), f);
    if (hi - lo != 1) continue;
    const Vec3& a = after.x[static_cast<std::size_t>(f[0])];
    area += 0.5 * (after.x[static_cast<std::size_t>(f[1])] - a)
                      .cross(after.x[static_cast<std::size_t>(f[2])] - a)
                      .norm();
  }
  return 0.5 * area;
}

double min_added_quality(const TetMesh& after, const TopologyDelta& delta) {
  double q = 1.0;
  for (std::int32_t slot : delta.slot_of_added) {
    const Tet& t = after.tets[static_cast<std::size_t>(slot)];
    q = std::min(q, tet_quality(after.rest[static_cast<std::size_t>(t[0])],
                                after.rest[static_cast<std::size_t>(t[1])],
                                after.rest[static_cast<std::size_t>(t[2])],
                                after.rest[static_cast<std::size_t>(t[3])]));
  }
  return q;
}

}  // namespace serosa::cutting
