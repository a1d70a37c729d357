#include "surface/cut_faces.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>

#include "engine/geometry/point_triangle.h"

namespace serosa::surface {
namespace {

constexpr double kRelTol = 1e-6;  // of the original triangle's longest edge
constexpr std::int64_t kCellBits = 21;
constexpr std::int64_t kCellMax = (std::int64_t{1} << kCellBits) - 1;

std::int64_t cell_index(double v) {
  if (!(v > 0.0)) return 0;  // also NaN
  return std::min<std::int64_t>(static_cast<std::int64_t>(v), kCellMax);
}

}  // namespace

OriginalSurface::OriginalSurface(const TetMesh& mesh, const SurfaceMesh& s) {
  const std::size_t n = s.faces.size();
  if (s.face_group.size() != n)
    throw std::invalid_argument("OriginalSurface: faces and face_group differ in size");
  tris_.resize(n);
  group_ = s.face_group;
  tol2_.resize(n);
  if (n == 0) return;

  // Corners, tolerances, the box and the mean edge (grid cell).
  Vec3 lo = Vec3::Constant(std::numeric_limits<double>::infinity());
  Vec3 hi = -lo;
  double edge_sum = 0.0;
  for (std::size_t i = 0; i < n; ++i) {
    for (int k = 0; k < 3; ++k) {
      const std::int32_t v = s.faces[i][static_cast<std::size_t>(k)];
      if (v < 0 || v >= mesh.num_nodes())
        throw std::invalid_argument("OriginalSurface: face " + std::to_string(i) + " names node " +
                                    std::to_string(v) + ", not in the mesh");
      tris_[i][static_cast<std::size_t>(k)] = mesh.rest[static_cast<std::size_t>(v)];
      lo = lo.cwiseMin(tris_[i][static_cast<std::size_t>(k)]);
      hi = hi.cwiseMax(tris_[i][static_cast<std::size_t>(k)]);
    }
    const auto& t = tris_[i];
    const double longest = std::sqrt(std::max(
        {(t[1] - t[0]).squaredNorm(), (t[2] - t[1]).squaredNorm(), (t[0] - t[2]).squaredNorm()}));
    tol2_[i] = (kRelTol * longest) * (kRelTol * longest);
    edge_sum += longest;
  }
  const double extent = (hi - lo).maxCoeff();
  cell_ = std::max({edge_sum / static_cast<double>(n), extent / static_cast<double>(kCellMax / 2),
                    std::numeric_limits<double>::min()});
  origin_ = lo - Vec3::Constant(cell_);

  // Each triangle goes into every cell its (tolerance-grown) box meets; then grouped by cell.
  std::vector<std::pair<std::uint64_t, std::int32_t>> entries;
  entries.reserve(n * 2);
  for (std::size_t i = 0; i < n; ++i) {
    const auto& t = tris_[i];
    const double pad = std::sqrt(tol2_[i]);
    const Vec3 blo = t[0].cwiseMin(t[1]).cwiseMin(t[2]) - Vec3::Constant(pad);
    const Vec3 bhi = t[0].cwiseMax(t[1]).cwiseMax(t[2]) + Vec3::Constant(pad);
    const Vec3 a = (blo - origin_) / cell_;
    const Vec3 b = (bhi - origin_) / cell_;
    for (std::int64_t x = cell_index(a.x()); x <= cell_index(b.x()); ++x)
      for (std::int64_t y = cell_index(a.y()); y <= cell_index(b.y()); ++y)
        for (std::int64_t z = cell_index(a.z()); z <= cell_index(b.z()); ++z)
          entries.emplace_back(
              static_cast<std::uint64_t>(x << (2 * kCellBits) | y << kCellBits | z),
              static_cast<std::int32_t>(i));
  }
  std::sort(entries.begin(), entries.end());
  cell_tris_.resize(entries.size());
  cells_.reserve(entries.size());
  for (std::size_t i = 0; i < entries.size();) {
    std::size_t j = i;
    while (j < entries.size() && entries[j].first == entries[i].first) {
      cell_tris_[j] = entries[j].second;
      ++j;
    }
    cells_.emplace(entries[i].first,
                   std::make_pair(static_cast<std::int32_t>(i), static_cast<std::int32_t>(j)));
    i = j;
  }
}

std::uint64_t OriginalSurface::cell_key(const Vec3& p) const {
  const Vec3 c = (p - origin_) / cell_;
  return static_cast<std::uint64_t>(cell_index(c.x()) << (2 * kCellBits) |
                                    cell_index(c.y()) << kCellBits | cell_index(c.z()));
}

bool OriginalSurface::contains(const Vec3& a, const Vec3& b, const Vec3& c, std::uint16_t g) const {
  if (tris_.empty()) return false;
  // A piece of an original triangle has its centroid inside that triangle, hence in a cell the
  // triangle was put into.
  const auto it = cells_.find(cell_key((a + b + c) / 3.0));
  if (it == cells_.end()) return false;
  for (std::int32_t k = it->second.first; k < it->second.second; ++k) {
    const auto i = static_cast<std::size_t>(cell_tris_[static_cast<std::size_t>(k)]);
    if (group_[i] != g) continue;
    const auto& t = tris_[i];
    if (geometry::closest_point_on_triangle(a, t[0], t[1], t[2]).dist2 <= tol2_[i] &&
        geometry::closest_point_on_triangle(b, t[0], t[1], t[2]).dist2 <= tol2_[i] &&
        geometry::closest_point_on_triangle(c, t[0], t[1], t[2]).dist2 <= tol2_[i])
      return true;
  }
  return false;
}

std::uint8_t classify_face(const Tri& f, std::uint16_t g, const TetMesh& mesh,
                           const OriginalSurface& original) {
  if (original.empty()) return 0;
  const auto& r = mesh.rest;
  return original.contains(r[static_cast<std::size_t>(f[0])], r[static_cast<std::size_t>(f[1])],
                           r[static_cast<std::size_t>(f[2])], g)
             ? 0
             : 1;
}

void mark_cut_faces(SurfaceMesh& s, const TetMesh& mesh, const OriginalSurface& original) {
  s.face_cut.assign(s.faces.size(), 0);
  if (original.empty()) return;
  const auto n = static_cast<std::int64_t>(s.faces.size());
#pragma omp parallel for schedule(static) if (n > 20000)
  for (std::int64_t i = 0; i < n; ++i) {
    const auto k = static_cast<std::size_t>(i);
    s.face_cut[k] = classify_face(s.faces[k], s.face_group[k], mesh, original);
  }
}

}  // namespace serosa::surface
