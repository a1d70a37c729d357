// Coplanar-face clipping (docs/cutting.md, point 5): which welded coplanar faces the blade
// covers partly, the crossings of their edges, their triangulation, and the pieces of the
// one-sided tets that hold them.
#include "cutting/cut_coplanar.h"

#include <limits>
#include <optional>

#include "cutting/cut_emit_tet.h"

namespace serosa::cutting::detail {
namespace {

// Counts, for every coplanar face of the candidates, how many candidates hold it (each face
// counted from its smallest node, so once per tet).
void count_coplanar_faces(CutState& cs) {
  for (const auto& [id, tets] : cs.zero_tets)
    for (std::int32_t ci : tets) {
      const TetInfo& info = cs.tets[static_cast<std::size_t>(ci)];
      const Tet& t = cs.mesh.tets[cs.cands[static_cast<std::size_t>(ci)]];
      for (const auto& f : kTetFaces) {
        if (!coplanar_face(info, f)) continue;
        const FaceKey key = face_key(t, f);
        if (key[0] != id) continue;
        ++cs.coplanar[key];
      }
    }
}

// The blade's corners inside face `key` (plane coordinates q, twice-signed area a2) by more than
// tol: corners of the clipped part, with barycentric weights in the face.
void add_blade_corners(const CutState& cs, const FaceKey& key, const std::array<V2, 3>& q,
                       double a2, ClipFace& cf) {
  for (std::size_t k = 0; k < cs.blade2.size(); ++k) {
    double margin = std::numeric_limits<double>::infinity();
    std::array<double, 3> w{};
    for (int i = 0; i < 3; ++i) {
      const V2 &u = q[static_cast<std::size_t>(i)], &v = q[(i + 1) % 3];
      const double ar = area2d(u, v, cs.blade2[k]);
      margin = std::min(margin, (a2 > 0.0 ? 2.0 : -2.0) * ar / (v - u).norm());
      w[(i + 2) % 3] = ar / a2;
    }
    if (!(margin > cs.tol)) continue;
    ClipCorner c;
    c.kind = ClipCorner::Kind::kBladeCorner;
    c.a = static_cast<int>(k);
    for (int i = 0; i < 3; ++i)
      c.combo.add(key[static_cast<std::size_t>(i)], w[static_cast<std::size_t>(i)]);
    c.p2 = cs.blade2[k];
    cf.corners.push_back(c);
  }
}

// Welded coplanar face `key` ∩ blade, when the blade covers the face only partly and the part
// has area (more than tol times the face's diameter).
std::optional<ClipFace> clip_face(CutState& cs, const FaceKey& key) {
  if (cs.nodes[key[0]].inside && cs.nodes[key[1]].inside && cs.nodes[key[2]].inside)
    return std::nullopt;
  const std::array<V2, 3> q{cs.blade.to_plane(cs.mesh.x[key[0]]),
                            cs.blade.to_plane(cs.mesh.x[key[1]]),
                            cs.blade.to_plane(cs.mesh.x[key[2]])};
  const double a2 = area2d(q[0], q[1], q[2]);
  if (!(std::abs(a2) > 0.0)) return std::nullopt;
  ClipFace cf;
  for (int k = 0; k < 3; ++k)
    if (cs.nodes[key[static_cast<std::size_t>(k)]].inside) {
      ClipCorner c;
      c.kind = ClipCorner::Kind::kNode;
      c.a = k;
      c.combo.add(key[static_cast<std::size_t>(k)], 1.0);
      c.p2 = q[static_cast<std::size_t>(k)];
      cf.corners.push_back(c);
    }
  for (int e = 0; e < 3; ++e) {
    const auto& fe = kFaceEdges[static_cast<std::size_t>(e)];
    const std::vector<CopPoint>& pts = cop_edge(cs, key[fe[0]], key[fe[1]]);
    for (std::size_t k = 0; k < pts.size(); ++k) {
      ClipCorner c;
      c.kind = ClipCorner::Kind::kEdgePoint;
      c.a = e;
      c.b = static_cast<int>(k);
      c.combo = pts[k].combo;
      c.p2 = (1.0 - pts[k].s) * q[fe[0]] + pts[k].s * q[fe[1]];
      cf.corners.push_back(c);
    }
  }
  double diam = 0.0;
  for (int k = 0; k < 3; ++k)
    diam = std::max(diam, (q[static_cast<std::size_t>(k)] - q[(k + 1) % 3]).norm());
  add_blade_corners(cs, key, q, a2, cf);
  if (cf.corners.size() < 3) return std::nullopt;
  auto p2 = [](const ClipCorner& c) -> const V2& { return c.p2; };
  const V2 c = sort_ccw(cf.corners, p2);
  if (!(fan_area_from(c, cf.corners, p2) > cs.tol * diam)) return std::nullopt;
  return cf;
}

// Only the edges of clipped faces, and the coplanar section sides partial tets stop the crack on
// (classify), keep their crossings and are split.
void keep_split_edges(CutState& cs) {
  std::unordered_map<std::uint64_t, std::vector<CopPoint>> kept;
  for (const auto& [key, cf] : cs.pfaces)
    for (const auto& fe : kFaceEdges) {
      const std::uint64_t k = edge_key(key[fe[0]], key[fe[1]]);
      if (!cs.cop_edges[k].empty()) kept.emplace(k, cs.cop_edges[k]);
    }
  for (const std::uint64_t k : cs.front_edges)
    if (!cs.cop_edges[k].empty()) kept.emplace(k, cs.cop_edges[k]);
  cs.cop_edges = std::move(kept);
}

// A partial tet holding a coplanar edge with crossings has them on its section's side
// (analyse_partial). A complete one cannot (both ends inside the convex blade), save in
// rounding: pinned.
void pin_complete_tets_on_split_edges(CutState& cs) {
  for (std::size_t ci = 0; ci < cs.cands.size(); ++ci) {
    TetInfo& info = cs.tets[ci];
    if (!info.straddles || !info.complete) continue;
    const Tet& t = cs.mesh.tets[cs.cands[ci]];
    for (int i = 0; i < 4; ++i)
      for (int j = i + 1; j < 4; ++j)
        if (info.sign[i] == Sign::kZero && info.sign[j] == Sign::kZero &&
            has_cop_points(cs, t[i], t[j])) {
          info.complete = false;
          info.pinned = true;
          info.interacts = true;
        }
  }
}

// Face `key`'s nodes, then the crossings on its edges (welded nodes), into ft.pts; returns, per
// edge (kFaceEdges), the indices of its crossings in ft.pts.
std::array<std::vector<int>, 3> add_face_nodes_and_crossings(CutState& cs, const FaceKey& key,
                                                             CopFaceTris& ft) {
  for (int k = 0; k < 3; ++k) {
    CopFacePoint p;
    p.node = key[static_cast<std::size_t>(k)];
    p.combo.add(p.node, 1.0);
    ft.pts.push_back(p);
  }
  std::array<std::vector<int>, 3> edge_idx;
  for (int e = 0; e < 3; ++e) {
    const auto& fe = kFaceEdges[static_cast<std::size_t>(e)];
    for (CopPoint& cp : cop_points(cs, key[fe[0]], key[fe[1]])) {
      CopFacePoint p;
      p.combo = cp.combo;
      p.pos = p.neg = cop_point_id(cs, cp);
      edge_idx[static_cast<std::size_t>(e)].push_back(static_cast<int>(ft.pts.size()));
      ft.pts.push_back(p);
    }
  }
  return edge_idx;
}

// The part of a clipped face under the blade: its corners (blade corners get welded nodes) in
// ft.pts, fanned from an opened pair of nodes at their mean. Returns the fan's edges as
// constraints of the face's triangulation.
std::vector<std::array<int, 2>> fan_clipped_part(CutState& cs, const ClipFace& cf,
                                                 const std::array<std::vector<int>, 3>& edge_idx,
                                                 CopFaceTris& ft) {
  std::vector<int> ring;
  Combo mean;
  const auto& corners = cf.corners;
  for (const ClipCorner& c : corners) {
    mean.add(c.combo, 1.0 / static_cast<double>(corners.size()));
    if (c.kind == ClipCorner::Kind::kNode) {
      ring.push_back(c.a);
    } else if (c.kind == ClipCorner::Kind::kEdgePoint) {
      ring.push_back(edge_idx[static_cast<std::size_t>(c.a)][static_cast<std::size_t>(c.b)]);
    } else {
      CopFacePoint p;
      p.combo = c.combo;
      p.pos = p.neg = cs.weld.add_point(c.combo.parent());
      ++cs.result.stats.face_points;
      ring.push_back(static_cast<int>(ft.pts.size()));
      ft.pts.push_back(p);
    }
  }
  CopFacePoint p;
  p.combo = mean;
  p.pos = cs.weld.add_point(mean.parent());
  p.neg = cs.weld.add_point(mean.parent());
  cs.result.stats.steiner_points += 2;
  const int centre = static_cast<int>(ft.pts.size());
  ft.pts.push_back(p);
  std::vector<std::array<int, 2>> constraints;
  for (std::size_t k = 0; k < ring.size(); ++k) {
    constraints.push_back({ring[k], ring[(k + 1) % ring.size()]});
    constraints.push_back({centre, ring[k]});
  }
  return constraints;
}

// The triangulation of coplanar face `key` (sorted), once per face so both tets holding it
// agree: its nodes, the crossings on its edges, and, when the blade covers it partly, the part
// under the blade fanned from an opened pair of nodes at its centroid.
const CopFaceTris& cop_face(CutState& cs, const FaceKey& key) {
  auto [it, fresh] = cs.cop_faces.try_emplace(key);
  if (!fresh) return it->second;
  CopFaceTris& ft = it->second;
  const std::array<std::vector<int>, 3> edge_idx = add_face_nodes_and_crossings(cs, key, ft);
  std::vector<std::array<int, 2>> constraints;
  const auto pf = cs.pfaces.find(key);
  if (pf != cs.pfaces.end()) constraints = fan_clipped_part(cs, pf->second, edge_idx, ft);
  std::vector<V2> uv;
  for (const CopFacePoint& p : ft.pts) uv.push_back(face_uv(p.combo, key));
  ft.tris = triangulate_section(uv, constraints, 1e-10);
  double area = 0.0;
  for (const auto& tr : ft.tris) area += area2d(uv[tr[0]], uv[tr[1]], uv[tr[2]]);
  if (!(std::abs(area - 0.5) <= 1e-9)) ++cs.result.stats.degenerate_tets;
  return ft;
}

// A one-sided tet with coplanar face `key`: coned from its off-plane node o over the face's
// triangulation, on side pos.
void emit_coned_over_face(CutState& cs, const FaceKey& key, std::int32_t o, bool pos,
                          std::uint16_t g) {
  const CopFaceTris& ft = cop_face(cs, key);
  const Combo co = Combo::of(o);
  for (const auto& tr : ft.tris) {
    std::array<std::int32_t, 4> ids{o, 0, 0, 0};
    for (int k = 0; k < 3; ++k) {
      const CopFacePoint& p = ft.pts[static_cast<std::size_t>(tr[static_cast<std::size_t>(k)])];
      ids[static_cast<std::size_t>(k + 1)] =
          p.node >= 0 ? node_id(cs, p.node, pos) : (pos ? p.pos : p.neg);
    }
    emit_tet(cs, ids,
             {&co, &ft.pts[static_cast<std::size_t>(tr[0])].combo,
              &ft.pts[static_cast<std::size_t>(tr[1])].combo,
              &ft.pts[static_cast<std::size_t>(tr[2])].combo},
             g);
  }
}

// A one-sided tet with one coplanar edge (a, b) with crossings q_k and opposite edge (c, d):
// pieces (q_k, q_k+1, c, d) along it, on side pos.
void emit_fanned_along_edge(CutState& cs, std::int32_t a, std::int32_t b, std::int32_t c,
                            std::int32_t d, bool pos, std::uint16_t g) {
  std::vector<CopPoint>& pts = cop_points(cs, a, b);
  std::vector<std::pair<std::int32_t, Combo>> chain;
  chain.emplace_back(node_id(cs, a, pos), Combo::of(a));
  for (CopPoint& p : pts) chain.emplace_back(cop_point_id(cs, p), p.combo);
  chain.emplace_back(node_id(cs, b, pos), Combo::of(b));
  const Combo cc = Combo::of(c), cd = Combo::of(d);
  for (std::size_t k = 0; k + 1 < chain.size(); ++k)
    emit_tet(cs, {chain[k].first, chain[k + 1].first, c, d},
             {&chain[k].second, &chain[k + 1].second, &cc, &cd}, g);
}

}  // namespace

std::vector<CopPoint>& cop_edge(CutState& cs, std::int32_t a, std::int32_t b) {
  auto [it, fresh] = cs.cop_edges.try_emplace(edge_key(a, b));
  if (fresh) {
    const std::int32_t lo = std::min(a, b), hi = std::max(a, b);
    for (double s : outline_crossings(cs, cs.blade.to_plane(cs.mesh.x[lo]),
                                      cs.blade.to_plane(cs.mesh.x[hi]))) {
      CopPoint p;
      p.s = s;
      p.combo.add(lo, 1.0 - s);
      p.combo.add(hi, s);
      it->second.push_back(p);
    }
  }
  return it->second;
}

std::vector<CopPoint>& cop_points(CutState& cs, std::int32_t a, std::int32_t b) {
  const auto it = cs.cop_edges.find(edge_key(a, b));
  return it == cs.cop_edges.end() ? cs.no_points : it->second;
}

bool has_cop_points(const CutState& cs, std::int32_t a, std::int32_t b) {
  const auto it = cs.cop_edges.find(edge_key(a, b));
  return it != cs.cop_edges.end() && !it->second.empty();
}

std::int32_t cop_point_id(CutState& cs, CopPoint& p) {
  if (p.id < 0) {
    p.id = cs.weld.add_point(p.combo.parent());
    ++cs.result.stats.face_points;
  }
  return p.id;
}

void decide_faces(CutState& cs) {
  count_coplanar_faces(cs);
  std::vector<FaceKey> welded;
  for (const auto& [key, count] : cs.coplanar)
    if (count >= 2) welded.push_back(key);
  std::sort(welded.begin(), welded.end());
  for (const FaceKey& key : welded)
    if (std::optional<ClipFace> cf = clip_face(cs, key)) cs.pfaces.emplace(key, std::move(*cf));
  keep_split_edges(cs);
  pin_complete_tets_on_split_edges(cs);
}

bool corner_inside(const CutState& cs, std::int32_t a, const FaceKey& key) {
  for (std::int32_t w : key) {
    if (w == a) continue;
    Vec3 next = cs.mesh.x[w];
    const auto it = cs.cop_edges.find(edge_key(a, w));
    if (it != cs.cop_edges.end() && !it->second.empty())
      next = (a < w ? it->second.front() : it->second.back()).combo.cur(cs.mesh);
    if (cs.blade.inside_margin(0.5 * (cs.mesh.x[a] + next)) < -cs.tol) return false;
  }
  return true;
}

bool needs_cop_split(const CutState& cs, const Tet& t, const TetInfo& info) {
  for (int i = 0; i < 4; ++i)
    for (int j = i + 1; j < 4; ++j)
      if (info.sign[i] == Sign::kZero && info.sign[j] == Sign::kZero &&
          has_cop_points(cs, t[i], t[j]))
        return true;
  for (const auto& f : kTetFaces)
    if (coplanar_face(info, f) && cs.pfaces.count(face_key(t, f)) > 0) return true;
  return false;
}

void emit_cop_split(CutState& cs, const Tet& t, const TetInfo& info, std::uint16_t g) {
  bool pos = false;
  std::vector<int> zeros, others;
  for (int k = 0; k < 4; ++k) {
    pos = pos || info.sign[k] == Sign::kPos;
    (info.sign[k] == Sign::kZero ? zeros : others).push_back(k);
  }
  if (zeros.size() == 3) {
    emit_coned_over_face(cs, face_key(t, {zeros[0], zeros[1], zeros[2]}), t[others[0]], pos, g);
    return;
  }
  emit_fanned_along_edge(cs, std::min(t[zeros[0]], t[zeros[1]]), std::max(t[zeros[0]], t[zeros[1]]),
                         t[others[0]], t[others[1]], pos, g);
}

}  // namespace serosa::cutting::detail
