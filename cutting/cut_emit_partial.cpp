// Partial tets' pieces (docs/cutting.md, point 5): each face of the tet is triangulated from
// data that belongs to the face alone (its nodes, the cut points that exist, the face points),
// so the tet on its other side triangulates it the same way, and the triangles are coned from
// the tet's apex.
#include "cutting/cut_emit_partial.h"

#include "cutting/cut_coplanar.h"
#include "cutting/cut_emit_tet.h"
#include "cutting/cut_partial.h"
#include "cutting/subdivide.h"

namespace serosa::cutting::detail {
namespace {

// One point of a face's triangulation: ids on the positive and negative side.
struct FPoint {
  Combo combo;
  std::int32_t pos = -1, neg = -1;
  Sign sign = Sign::kZero;  ///< original nodes: their sign; points on the plane: kZero
};

// Side of a triangle from its original nodes: +1, -1, or 0 when it crosses the plane.
int tri_side(const FPoint& a, const FPoint& b, const FPoint& c) {
  bool p = false, n = false;
  for (const FPoint* q : {&a, &b, &c}) {
    p = p || q->sign == Sign::kPos;
    n = n || q->sign == Sign::kNeg;
  }
  return p && n ? 0 : p ? 1 : -1;
}

// Index in pts of the point with exactly combo c's parents and weights, or -1.
int find_point(const std::vector<FPoint>& pts, const Combo& c) {
  for (std::size_t k = 0; k < pts.size(); ++k) {
    const Combo& q = pts[k].combo;
    bool same = q.count == c.count;
    for (int l = 0; l < c.count && same; ++l) {
      bool found = false;
      for (int m = 0; m < q.count; ++m)
        found = found || (q.nodes[m] == c.nodes[l] && q.w[m] == c.w[l]);
      same = found;
    }
    if (same) return static_cast<int>(k);
  }
  return -1;
}

// Tet face f (local node triple) of a partial tet, triangulated so that both tets sharing it
// agree, coned from the apex (aid, apex). Faces on one side: whole, or fanned along a coplanar
// edge with crossings. Crossed faces without face points: split_face (the patterns' rule) at the
// cut points that exist. Crossed faces with face points: the constrained triangulation
// (cutting/section_triangulation.h) of the face's nodes, existing cut points and face points, in
// affine coordinates from the face's sorted node ids, with the section side's parts inside the
// blade as constraints.
class PartialFace {
 public:
  PartialFace(CutState& cs, const Tet& t, const TetInfo& info, const std::array<int, 3>& f,
              std::int32_t aid, const Combo& apex, std::uint16_t g)
      : m_cs(cs), m_t(t), m_info(info), m_f(f), m_aid(aid), m_apex(apex), m_g(g) {}

  void emit() {
    bool has_pos = false, has_neg = false;
    for (int i : m_f) {
      has_pos = has_pos || m_info.sign[i] == Sign::kPos;
      has_neg = has_neg || m_info.sign[i] == Sign::kNeg;
    }
    if (!(has_pos && has_neg)) {  // the whole face on one side
      if (!emit_along_coplanar_edge()) emit_tri(node_point(0), node_point(1), node_point(2));
      return;
    }
    std::array<bool, 3> has_edge{false, false, false};
    const std::array<FPoint, 6> fp = points_with_cut_points(has_edge);
    const FaceKey key = face_key(m_t, m_f);
    const auto fit = m_cs.faces.find(key);
    if (fit == m_cs.faces.end() || fit->second.points.empty()) {
      emit_split_face(fp, has_edge);
      return;
    }
    std::vector<FPoint> pts;
    for (int k = 0; k < 6; ++k)
      if (k < 3 || has_edge[static_cast<std::size_t>(k - 3)])
        pts.push_back(fp[static_cast<std::size_t>(k)]);
    emit_with_face_points(key, fit->second, pts);
  }

 private:
  // The face's node k (0..2 in m_f).
  FPoint node_point(int k) const {
    FPoint p;
    const std::int32_t v = m_t[m_f[k]];
    p.combo.add(v, 1.0);
    p.pos = node_id(m_cs, v, true);
    p.neg = v;
    p.sign = m_info.sign[m_f[k]];
    return p;
  }

  void cone(const FPoint& a, const FPoint& b, const FPoint& c, bool pos) {
    emit_tet(m_cs, {m_aid, pos ? a.pos : a.neg, pos ? b.pos : b.neg, pos ? c.pos : c.neg},
             {&m_apex, &a.combo, &b.combo, &c.combo}, m_g);
  }

  // Cones triangle (a, b, c) on its side; a triangle across the plane goes with the positive
  // side, and only welded points may lie on it.
  void emit_tri(const FPoint& a, const FPoint& b, const FPoint& c) {
    const int side = tri_side(a, b, c);
    if (side == 0) {
      for (const FPoint* q : {&a, &b, &c})
        if (q->pos != q->neg) ++m_cs.result.stats.degenerate_tets;
    }
    cone(a, b, c, side >= 0);
  }

  // A one-sided face holding a coplanar edge with crossings (decide_faces): fanned from the
  // face's third node. False when it holds none.
  bool emit_along_coplanar_edge() {
    for (int k = 0; k < 3; ++k) {
      const int i = m_f[k], j = m_f[(k + 1) % 3];
      if (m_info.sign[i] != Sign::kZero || m_info.sign[j] != Sign::kZero ||
          !has_cop_points(m_cs, m_t[i], m_t[j]))
        continue;
      const std::int32_t lo = std::min(m_t[i], m_t[j]), hi = std::max(m_t[i], m_t[j]);
      std::vector<FPoint> chain{node_point(m_t[i] == lo ? k : (k + 1) % 3)};
      for (CopPoint& cp : cop_points(m_cs, lo, hi)) {
        FPoint p;
        p.combo = cp.combo;
        p.pos = p.neg = cop_point_id(m_cs, cp);
        chain.push_back(p);
      }
      chain.push_back(node_point(m_t[i] == lo ? (k + 1) % 3 : k));
      const FPoint third = node_point((k + 2) % 3);
      for (std::size_t l = 0; l + 1 < chain.size(); ++l) emit_tri(chain[l], chain[l + 1], third);
      return true;
    }
    return false;
  }

  // The face's nodes (0..2) and the cut points of its crossing edges that exist (inside the
  // polygon; 3 + k for edge (k, k + 1), has_edge[k] set).
  std::array<FPoint, 6> points_with_cut_points(std::array<bool, 3>& has_edge) {
    std::array<FPoint, 6> fp{node_point(0), node_point(1), node_point(2), {}, {}, {}};
    for (int k = 0; k < 3; ++k) {
      const int i = m_f[k], j = m_f[(k + 1) % 3];
      if (!crossing_edge(m_info, i, j)) continue;
      const EdgeInfo& e = m_cs.edges.at(edge_key(m_t[i], m_t[j]));
      if (!e.inside) continue;
      has_edge[static_cast<std::size_t>(k)] = true;
      FPoint& p = fp[static_cast<std::size_t>(3 + k)];
      p.pos = edge_point_id(m_cs, m_t[i], m_t[j], true, p.combo);
      Combo unused;
      p.neg = edge_point_id(m_cs, m_t[i], m_t[j], false, unused);
    }
    return fp;
  }

  // A crossed face without face points: split_face with this side's ids, once per side;
  // triangles across the plane from the positive call.
  void emit_split_face(const std::array<FPoint, 6>& fp, const std::array<bool, 3>& has_edge) {
    for (const bool pos : {true, false}) {
      std::array<std::int32_t, 6> ids{-1, -1, -1, -1, -1, -1};
      for (int k = 0; k < 6; ++k)
        if (k < 3 || has_edge[static_cast<std::size_t>(k - 3)])
          ids[static_cast<std::size_t>(k)] =
              pos ? fp[static_cast<std::size_t>(k)].pos : fp[static_cast<std::size_t>(k)].neg;
      const FaceSplit fs = split_face(ids);
      for (int k = 0; k < fs.count; ++k) {
        const auto& tr = fs.tris[static_cast<std::size_t>(k)];
        const FPoint &a = fp[tr[0]], &b = fp[tr[1]], &c = fp[tr[2]];
        const int side = tri_side(a, b, c);
        if (side == (pos ? 1 : -1) || (pos && side == 0)) emit_tri(a, b, c);
      }
    }
  }

  // The section side's two endpoints in this face (coplanar nodes or cut points), as
  // (label, combo), the smaller label first; empty when there are not two (degenerate).
  std::vector<std::pair<std::uint64_t, Combo>> section_side_ends() const {
    std::vector<std::pair<std::uint64_t, Combo>> ends;
    for (int k = 0; k < 3; ++k) {
      const int i = m_f[k], j = m_f[(k + 1) % 3];
      if (m_info.sign[i] == Sign::kZero)
        ends.emplace_back(edge_key(m_t[i], m_t[i]), Combo::of(m_t[i]));
      if (crossing_edge(m_info, i, j)) {
        const EdgeInfo& e = m_cs.edges.at(edge_key(m_t[i], m_t[j]));
        ends.emplace_back(edge_key(m_t[i], m_t[j]), edge_combo(m_t[i], m_t[j], e.t));
      }
    }
    if (ends.size() != 2) return {};
    if (ends[1].first < ends[0].first) std::swap(ends[0], ends[1]);
    return ends;
  }

  // A crossed face with face points (entry): pts holds its nodes and existing cut points; the
  // face points are added, and the face is triangulated with the section side's parts under
  // the blade as constraints.
  void emit_with_face_points(const FaceKey& key, FaceEntry& entry, std::vector<FPoint>& pts) {
    const auto ends = section_side_ends();
    if (ends.empty()) {
      ++m_cs.result.stats.degenerate_tets;
      return;
    }
    // Points along the side, from the smaller label: index into pts or -1 (a missing cut point).
    std::vector<int> along{find_point(pts, ends[0].second)};
    std::vector<Combo> along_combo{ends[0].second};
    for (FacePoint& q : entry.points) {
      FPoint p;
      p.combo = q.combo;
      p.pos = p.neg = face_point_id(m_cs, q);
      along.push_back(static_cast<int>(pts.size()));
      along_combo.push_back(q.combo);
      pts.push_back(p);
    }
    along.push_back(find_point(pts, ends[1].second));
    along_combo.push_back(ends[1].second);
    std::vector<std::array<int, 2>> constraints;
    for (std::size_t k = 0; k + 1 < along.size(); ++k) {
      if (along[k] < 0 || along[k + 1] < 0) continue;
      Combo mid;
      mid.add(along_combo[k], 0.5);
      mid.add(along_combo[k + 1], 0.5);
      if (m_cs.blade.inside_margin(mid.cur(m_cs.mesh)) >= 0.0)
        constraints.push_back({along[k], along[k + 1]});
    }
    std::vector<V2> uv;
    for (const FPoint& p : pts) uv.push_back(face_uv(p.combo, key));
    const auto tris = triangulate_section(uv, constraints, 1e-10);
    double area = 0.0;
    for (const auto& tr : tris) {
      area += area2d(uv[tr[0]], uv[tr[1]], uv[tr[2]]);
      emit_tri(pts[tr[0]], pts[tr[1]], pts[tr[2]]);
    }
    if (!(std::abs(area - 0.5) <= 1e-9)) ++m_cs.result.stats.degenerate_tets;
  }

  CutState& m_cs;
  const Tet& m_t;
  const TetInfo& m_info;
  const std::array<int, 3>& m_f;
  std::int32_t m_aid;   ///< the apex's node
  const Combo& m_apex;  ///< the apex's parents
  std::uint16_t m_g;    ///< the tet's group
};

}  // namespace

void emit_partial(CutState& cs, const Tet& t, const TetInfo& info, std::uint16_t g) {
  Combo apex = info.apex;
  if (info.pinned && info.has_centre) {
    apex = info.centre;
  } else if (info.pinned) {
    apex = Combo{};
    for (int k = 0; k < 4; ++k) apex.add(t[k], 0.25);
  }
  const std::int32_t aid = cs.weld.add_point(apex.parent());
  ++cs.result.stats.steiner_points;
  for (const auto& f : kTetFaces) PartialFace(cs, t, info, f, aid, apex, g).emit();
}

}  // namespace serosa::cutting::detail
