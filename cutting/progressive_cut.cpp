#include "cutting/progressive_cut.h"

#include "cutting/planar_hull.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "engine/geometry/tet_extent.h"

namespace serosa::cutting {
namespace {

using V2 = Eigen::Vector2d;

double cross2(const V2& o, const V2& a, const V2& b) {
  return (a.x() - o.x()) * (b.y() - o.y()) - (a.y() - o.y()) * (b.x() - o.x());
}

}  // namespace

std::optional<ConvexPolygon> convex_union(const ConvexPolygon& a, const ConvexPolygon& b,
                                          double plane_rel, double area_rel) {
  const Vec3 lo = a.box_min().cwiseMin(b.box_min()), hi = a.box_max().cwiseMax(b.box_max());
  const double size = (hi - lo).norm();
  if (!(size > 0.0)) return std::nullopt;
  for (const Vec3& p : b.points())
    if (!(std::abs(a.signed_distance(p)) <= plane_rel * size)) return std::nullopt;
  // Both outlines in a's plane coordinates, counter-clockwise about a's normal.
  std::vector<V2> pa, pb;
  for (const Vec3& p : a.points()) pa.push_back(a.to_plane(p));
  for (const Vec3& p : b.points()) pb.push_back(a.to_plane(p));
  // (a's own outline is counter-clockwise in its own frame; b's may turn the other way.)
  if (signed_area(pb) < 0.0) std::reverse(pb.begin(), pb.end());
  const double overlap = std::abs(signed_area(clip_convex(pb, pa)));
  const double union_area = std::abs(signed_area(pa)) + std::abs(signed_area(pb)) - overlap;
  // The hull of every corner (Andrew's monotone chain; points closer than 1e-12 of the size
  // merged, collinear points dropped), keeping each hull point's world position.
  struct P {
    V2 q;
    Vec3 x;
  };
  std::vector<P> pts;
  for (std::size_t k = 0; k < pa.size(); ++k) pts.push_back({pa[k], a.points()[k]});
  for (std::size_t k = 0; k < pb.size(); ++k)
    pts.push_back({a.to_plane(b.points()[k]), b.points()[k]});
  std::sort(pts.begin(), pts.end(), [](const P& u, const P& w) {
    return u.q.x() < w.q.x() || (u.q.x() == w.q.x() && u.q.y() < w.q.y());
  });
  std::vector<P> uniq;
  for (const P& p : pts) {
    bool dup = false;
    for (const P& u : uniq) dup = dup || (u.q - p.q).norm() <= 1e-12 * size;
    if (!dup) uniq.push_back(p);
  }
  if (uniq.size() < 3) return std::nullopt;
  std::vector<P> hull(2 * uniq.size());
  std::size_t k = 0;
  for (std::size_t i = 0; i < uniq.size(); ++i) {
    while (k >= 2 && cross2(hull[k - 2].q, hull[k - 1].q, uniq[i].q) <= 0.0) --k;
    hull[k++] = uniq[i];
  }
  for (std::size_t i = uniq.size() - 1, lower = k + 1; i-- > 0;) {
    while (k >= lower && cross2(hull[k - 2].q, hull[k - 1].q, uniq[i].q) <= 0.0) --k;
    hull[k++] = uniq[i];
  }
  hull.resize(k - 1);
  std::vector<V2> h2;
  std::vector<Vec3> corners;
  for (const P& p : hull) {
    h2.push_back(p.q);
    corners.push_back(p.x);
  }
  const double hull_area = signed_area(h2);
  if (!(hull_area - union_area <= area_rel * hull_area)) return std::nullopt;
  // Counter-clockwise about a's normal: the union keeps a's orientation (its positive side).
  return ConvexPolygon::make(std::move(corners));
}

// One step of the stroke: the region swept so far grows by the blade; a new stroke is one plain
// cut, a continued one re-cuts the mesh before the stroke around the region and composes the
// result with the pieces it replaces.
CutResult ProgressiveCut::cut(const TetMesh& mesh, const ConvexPolygon& blade,
                              const TetBoxQuery& query) {
  m_pending.reset();
  m_last = {};
  if (m_region && mesh.topology_version != m_version) end();
  std::optional<ConvexPolygon> region;
  if (m_region) {
    region = convex_union(*m_region, blade);
    if (!region) end();
  }
  if (region) {
    m_last.extended = true;
    if (region->area() <= m_region->area() * (1.0 + 1e-12)) {
      // Nothing new swept: the region is already cut.
      m_last.inside = true;
      m_pending = Pending{m_region, {}, 0, m_nodes, true, mesh.topology_version, 0, 0, m_tolerance};
      CutResult none;
      none.stats.tolerance_m = m_tolerance;
      return none;
    }
  } else {
    region = blade;
  }
  const TetBoxQuery brute = query ? TetBoxQuery{} : brute_force_query(mesh);
  const TetBoxQuery& q = query ? query : brute;
  if (!m_region) return start_stroke(mesh, *region, q);
  const auto [tol, h] = stroke_tolerance(mesh, *region, q);
  const LocalRegion local = pre_stroke_region(mesh, *region, q, tol, h);
  CutOptions local_options = m_options;
  local_options.tolerance_m = tol;
  CutResult lr = cut_mesh(local.mesh, *region, local_options);
  return compose(mesh, *region, local, std::move(lr));
}

// A new stroke: the mesh is the mesh before it. One plain cut; all it removes are originals, all
// it adds the stroke's pieces.
CutResult ProgressiveCut::start_stroke(const TetMesh& mesh, const ConvexPolygon& region,
                                       const TetBoxQuery& q) {
  CutResult r = cut_mesh(mesh, region, m_options, q);
  Pending next;
  for (std::int32_t t : r.delta.removed_tets)
    next.originals.push_back(
        {mesh.tets[static_cast<std::size_t>(t)], mesh.group[static_cast<std::size_t>(t)]});
  next.region = region;
  next.pieces = r.delta.added_tets.size();
  next.nodes = static_cast<std::int32_t>(r.delta.added_nodes.size());
  next.version = mesh.topology_version;
  next.removed = r.delta.removed_tets.size();
  next.added = r.delta.added_tets.size();
  next.tolerance_m = r.stats.tolerance_m;
  m_pending = std::move(next);
  return r;
}

bool ProgressiveCut::is_piece(std::int32_t t) const {
  return std::binary_search(m_pieces.begin(), m_pieces.end(), t);
}

// The tolerance cut_mesh would take on the mesh before the stroke, and the longest edge of the tets
// the region's box meets (current tets less the stroke's pieces, plus its originals) it is
// relative to, m.
std::pair<double, double> ProgressiveCut::stroke_tolerance(const TetMesh& mesh,
                                                           const ConvexPolygon& region,
                                                           const TetBoxQuery& q) const {
  auto meets = [&](const Tet& t) {
    Vec3 tlo, thi;
    geometry::tet_box(mesh, t, tlo, thi);
    return (tlo.array() <= region.box_max().array()).all() &&
           (thi.array() >= region.box_min().array()).all();
  };
  std::vector<std::int32_t> cands;
  q(region.box_min(), region.box_max(), cands);
  double h = 0.0;
  for (std::int32_t t : cands)
    if (!is_piece(t) && meets(mesh.tets[static_cast<std::size_t>(t)]))
      h = std::max(h, geometry::longest_edge_m(mesh, mesh.tets[static_cast<std::size_t>(t)]));
  for (const Original& o : m_originals)
    if (meets(o.tet)) h = std::max(h, geometry::longest_edge_m(mesh, o.tet));
  return {m_options.tolerance_m > 0.0 ? m_options.tolerance_m : m_options.classify_rel * h, h};
}

// The mesh before the stroke, around the region: the current tets the region's box grown by twice
// the tolerance meets (every tet the cut looks at), less the stroke's pieces, plus the stroke's
// originals; of those, only tets with a node within twice the tolerance of the plane (the others
// are one-sided, and no decision of the cut depends on them). Local node ids follow the order of
// the mesh's ids, so that every rule keyed by the smallest node id (quad diagonals, face fans)
// decides as it would in the whole mesh.
ProgressiveCut::LocalRegion ProgressiveCut::pre_stroke_region(const TetMesh& mesh,
                                                              const ConvexPolygon& region,
                                                              const TetBoxQuery& q, double tol,
                                                              double h) const {
  const Vec3 grow = Vec3::Constant(2.0 * tol + 1e-12 * (1.0 + h));
  std::vector<std::int32_t> cands;
  q(region.box_min() - grow, region.box_max() + grow, cands);
  std::sort(cands.begin(), cands.end());
  cands.erase(std::unique(cands.begin(), cands.end()), cands.end());
  auto near_plane = [&](const Tet& t) {
    double lo = std::numeric_limits<double>::infinity(), hi = -lo;
    for (std::int32_t v : t) {
      const double phi = region.signed_distance(mesh.x[static_cast<std::size_t>(v)]);
      lo = std::min(lo, phi);
      hi = std::max(hi, phi);
    }
    return lo <= 2.0 * tol && hi >= -2.0 * tol;
  };
  LocalRegion out;
  std::vector<Tet> tets;
  std::vector<std::uint16_t> groups;
  for (std::size_t k = 0; k < m_originals.size(); ++k) {  // all of them: each is cut or put back
    tets.push_back(m_originals[k].tet);
    groups.push_back(m_originals[k].group);
    out.origin.push_back(-1 - static_cast<std::int32_t>(k));
  }
  for (std::int32_t t : cands)
    if (!is_piece(t) && near_plane(mesh.tets[static_cast<std::size_t>(t)])) {
      tets.push_back(mesh.tets[static_cast<std::size_t>(t)]);
      groups.push_back(mesh.group[static_cast<std::size_t>(t)]);
      out.origin.push_back(t);
    }
  std::vector<std::int32_t>& global_of = out.global_of;
  for (const Tet& t : tets) global_of.insert(global_of.end(), t.begin(), t.end());
  std::sort(global_of.begin(), global_of.end());
  global_of.erase(std::unique(global_of.begin(), global_of.end()), global_of.end());
  for (std::int32_t g : global_of) {
    out.mesh.rest.push_back(mesh.rest[static_cast<std::size_t>(g)]);
    out.mesh.x.push_back(mesh.x[static_cast<std::size_t>(g)]);
  }
  for (std::size_t k = 0; k < tets.size(); ++k) {
    Tet lt{};
    for (int i = 0; i < 4; ++i)
      lt[i] = static_cast<std::int32_t>(
          std::lower_bound(global_of.begin(), global_of.end(), tets[k][i]) - global_of.begin());
    out.mesh.tets.push_back(lt);
    out.mesh.group.push_back(groups[k]);
  }
  out.mesh.fill_node_state();
  return out;
}

// Compose: remove the stroke's pieces and the current tets the cut removes; add the cut's pieces
// (local ids mapped back, new nodes appended after the mesh's), then the originals the cut leaves
// whole.
CutResult ProgressiveCut::compose(const TetMesh& mesh, const ConvexPolygon& region,
                                  const LocalRegion& local, CutResult lr) {
  const TopologyDelta& ld = lr.delta;
  const std::int32_t n_cur = mesh.num_nodes();
  const auto n_local = static_cast<std::int32_t>(local.global_of.size());
  auto global_node = [&](std::int32_t l) {
    return l < n_local ? local.global_of[static_cast<std::size_t>(l)] : n_cur + (l - n_local);
  };
  TopologyDelta out;
  out.removed_tets = m_pieces;
  std::vector<char> cut_original(m_originals.size(), 0);
  Pending next;
  for (std::int32_t lt : ld.removed_tets) {
    const std::int32_t o = local.origin[static_cast<std::size_t>(lt)];
    if (o >= 0) {
      out.removed_tets.push_back(o);
      next.originals.push_back(
          {mesh.tets[static_cast<std::size_t>(o)], mesh.group[static_cast<std::size_t>(o)]});
    } else {
      cut_original[static_cast<std::size_t>(-1 - o)] = 1;
      next.originals.push_back(m_originals[static_cast<std::size_t>(-1 - o)]);
    }
  }
  std::sort(out.removed_tets.begin(), out.removed_tets.end());
  for (std::size_t k = 0; k < ld.added_tets.size(); ++k) {
    const Tet& t = ld.added_tets[k];
    out.added_tets.push_back(
        {global_node(t[0]), global_node(t[1]), global_node(t[2]), global_node(t[3])});
    out.added_groups.push_back(ld.added_groups[k]);
  }
  for (std::size_t k = 0; k < m_originals.size(); ++k)
    if (!cut_original[k]) {
      out.added_tets.push_back(m_originals[k].tet);
      out.added_groups.push_back(m_originals[k].group);
      ++m_last.originals_restored;
    }
  for (const NodeParent& p : ld.added_nodes) {
    NodeParent g = p;
    for (int k = 0; k < p.count; ++k)
      g.nodes[static_cast<std::size_t>(k)] = global_node(p.nodes[k]);
    out.added_nodes.push_back(g);
  }
  m_last.pieces_replaced = static_cast<std::int64_t>(m_pieces.size());
  m_last.nodes_released = m_nodes;
  next.region = region;
  next.pieces = ld.added_tets.size();
  next.nodes = static_cast<std::int32_t>(ld.added_nodes.size());
  next.version = mesh.topology_version;
  next.removed = out.removed_tets.size();
  next.added = out.added_tets.size();
  next.tolerance_m = lr.stats.tolerance_m;
  m_pending = std::move(next);
  lr.delta = std::move(out);
  return lr;
}

void ProgressiveCut::applied(const TetMesh& mesh, const TopologyDelta& delta) {
  if (!m_pending) return;
  Pending p = std::move(*m_pending);
  m_pending.reset();
  // The delta cut() returned, applied to the mesh it was made for: same sizes, and (when it
  // changed anything) made against that version, with the slots apply() filled in.
  bool ours = delta.removed_tets.size() == p.removed && delta.added_tets.size() == p.added;
  if (ours && !delta.empty())
    ours = delta.version_before == p.version && delta.version_after == mesh.topology_version &&
           delta.slot_of_added.size() == p.added;
  if (ours && delta.empty())
    ours = mesh.topology_version == p.version || delta.version_before == p.version;
  if (!ours) {
    end();
    return;
  }
  if (!p.keep) {
    m_pieces.assign(delta.slot_of_added.begin(),
                    delta.slot_of_added.begin() + static_cast<std::ptrdiff_t>(p.pieces));
    std::sort(m_pieces.begin(), m_pieces.end());
    m_originals = std::move(p.originals);
    m_nodes = p.nodes;
  }
  m_region = std::move(p.region);
  m_tolerance = p.tolerance_m;
  m_version = mesh.topology_version;
}

void ProgressiveCut::end() {
  m_region.reset();
  m_originals.clear();
  m_pieces.clear();
  m_nodes = 0;
  m_pending.reset();
}

}  // namespace serosa::cutting
