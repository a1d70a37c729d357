#include "cutting/flat_cut.h"

#include <algorithm>
#include <cmath>

#include "cutting/cut_areas.h"
#include "cutting/tet_bvh.h"
#include "engine/geometry/tet_barycentric.h"
#include "engine/geometry/tet_extent.h"

namespace serosa::cutting {
namespace {

double tet_volume(const std::array<Vec3, 4>& x) { return signed_volume(x[0], x[1], x[2], x[3]); }

// Tets whose flattened boxes meet [lo, hi] (flattened, m), their nodes flattened in mesh.x:
// flattening moves a point by at most the terrain's largest height, so the real boxes that can
// hold them meet [lo, hi] grown by it.
void flattened_query(FlattenedScope& scope, const TetMesh& mesh, const TetBvh& bvh, double reach,
                     const Vec3& lo, const Vec3& hi, std::vector<std::int32_t>& out) {
  std::vector<std::int32_t> near;
  const Vec3 grow = Vec3::Constant(reach);
  bvh.query(lo - grow, hi + grow, near);
  for (std::int32_t t : near) {
    scope.flatten_tet(t);
    Vec3 tlo, thi;
    geometry::tet_box(mesh, mesh.tets[static_cast<std::size_t>(t)], tlo, thi);
    if ((tlo.array() <= hi.array()).all() && (thi.array() >= lo.array()).all()) out.push_back(t);
  }
}

double reach(const FlattenedPositions& flat) {
  return flat.surface().max_abs_height() * 1.001 + 1e-9;
}

}  // namespace

const Vec3& FlattenedPositions::of(const TetMesh& mesh, std::int32_t n) {
  const auto i = static_cast<std::size_t>(n);
  if (m_x.size() < mesh.x.size()) {
    m_x.resize(mesh.x.size());
    m_has.resize(mesh.x.size(), 0);
  }
  if (m_has[i] == 0) {
    m_x[i] = m_surface.flatten(mesh.x[i]);
    m_has[i] = 1;
  }
  return m_x[i];
}

void FlattenedPositions::added(const TetMesh& mesh, const TopologyDelta& delta) {
  const std::size_t first = mesh.x.size() - delta.added_nodes.size();
  m_x.resize(mesh.x.size());
  m_has.resize(mesh.x.size(), 0);
  for (std::size_t k = 0; k < delta.added_nodes.size(); ++k) {
    const NodeParent& p = delta.added_nodes[k];
    Vec3 x = Vec3::Zero();
    for (int j = 0; j < p.count; ++j)
      x += p.weights[static_cast<std::size_t>(j)] * of(mesh, p.nodes[static_cast<std::size_t>(j)]);
    m_x[first + k] = x;
    m_has[first + k] = 1;
  }
}

void FlattenedScope::flatten_tet(std::int32_t t) {
  if (m_slot.size() < m_mesh.x.size()) m_slot.resize(m_mesh.x.size(), 0);
  for (std::int32_t n : m_mesh.tets[static_cast<std::size_t>(t)]) {
    const auto i = static_cast<std::size_t>(n);
    if (m_slot[i] != 0) continue;
    const Vec3 flat = m_flat.of(m_mesh, n);  // (from the real position: not yet swapped)
    m_nodes.push_back(n);
    m_saved.push_back(m_mesh.x[i]);
    m_slot[i] = static_cast<std::int32_t>(m_nodes.size());
    m_mesh.x[i] = flat;
  }
}

Vec3 FlattenedScope::real(std::int32_t n) const {
  const auto i = static_cast<std::size_t>(n);
  if (i >= m_slot.size() || m_slot[i] == 0) return m_mesh.x[i];
  return m_saved[static_cast<std::size_t>(m_slot[i] - 1)];
}

void FlattenedScope::restore() {
  for (std::size_t k = 0; k < m_nodes.size(); ++k) {
    m_mesh.x[static_cast<std::size_t>(m_nodes[k])] = m_saved[k];
    m_slot[static_cast<std::size_t>(m_nodes[k])] = 0;
  }
  m_nodes.clear();
  m_saved.clear();
}

bool flattening_keeps_tets(TetMesh& mesh, FlattenedPositions& flat,
                           const std::vector<ConvexPolygon>& polygons, const TetBvh& bvh) {
  if (polygons.empty()) return true;
  Vec3 lo = polygons[0].box_min(), hi = polygons[0].box_max();
  double size = 0.0;
  for (const ConvexPolygon& p : polygons) {
    lo = lo.cwiseMin(p.box_min());
    hi = hi.cwiseMax(p.box_max());
    size = std::max(size, p.diameter());
  }
  const Vec3 margin = Vec3::Constant(1e-3 * size + 1e-9);
  std::vector<std::int32_t> tets;
  std::vector<std::array<Vec3, 4>> real;
  {
    FlattenedScope scope(mesh, flat);
    flattened_query(scope, mesh, bvh, reach(flat), lo - margin, hi + margin, tets);
    for (std::int32_t t : tets) {
      const Tet& tet = mesh.tets[static_cast<std::size_t>(t)];
      std::array<Vec3, 4> r, f;
      for (int k = 0; k < 4; ++k) {
        r[static_cast<std::size_t>(k)] = scope.real(tet[k]);
        f[static_cast<std::size_t>(k)] = mesh.x[static_cast<std::size_t>(tet[k])];
      }
      const double vr = tet_volume(r), vf = tet_volume(f);
      if (!(vf / vr >= kMinFlattenedVolumeRatio)) return false;
    }
  }
  return true;
}

FlatCutResult cut_flattened(TetMesh& mesh, FlattenedPositions& flat, const ConvexPolygon& polygon,
                            const CutOptions& options, const TetBvh& bvh) {
  FlatCutResult out;
  FlattenedScope scope(mesh, flat);
  const double r = reach(flat);
  const TetBoxQuery query = [&](const Vec3& lo, const Vec3& hi, std::vector<std::int32_t>& res) {
    flattened_query(scope, mesh, bvh, r, lo, hi, res);
  };
  out.cut = cut_mesh(mesh, polygon, options, query);
  if (!out.cut.delta.empty())
    out.swept_area_m2 = swept_area(mesh, out.cut.delta.removed_tets, polygon);
  return out;
}

double flattened_crack_area(TetMesh& after, FlattenedPositions& flat, const TopologyDelta& delta,
                            const ConvexPolygon& polygon, double tol_m) {
  FlattenedScope scope(after, flat);
  for (std::int32_t t : delta.slot_of_added) scope.flatten_tet(t);
  return crack_area(after, delta, polygon, tol_m);
}

double crack_deviation(const TetMesh& mesh, const TetBvh& bvh, std::span<const Vec3> points,
                       const PlaneFit& fit, FlattenedPositions* flat) {
  double worst = 0.0;
  std::vector<std::int32_t> near;
  for (const Vec3& p : points) {
    near.clear();
    if (p.allFinite()) bvh.query(p, p, near);
    for (std::int32_t t : near) {
      const auto w = geometry::tet_barycentric(p, mesh, t);
      if (!w || *std::min_element(w->begin(), w->end()) < -1e-9) continue;
      Vec3 x = p;
      if (flat) {
        x = Vec3::Zero();
        const Tet& tet = mesh.tets[static_cast<std::size_t>(t)];
        for (std::size_t k = 0; k < 4; ++k) x += (*w)[k] * flat->of(mesh, tet[k]);
      }
      worst = std::max(worst, std::abs(fit.normal.dot(x - fit.centroid)));
      break;
    }
  }
  return worst;
}

TetMesh flattened_copy(const TetMesh& mesh, FlattenedPositions& flat) {
  TetMesh copy = mesh;
  for (std::int32_t n = 0; n < mesh.num_nodes(); ++n)
    copy.x[static_cast<std::size_t>(n)] = flat.of(mesh, n);
  return copy;
}

}  // namespace serosa::cutting
