#include "cutting/snap_cut.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <unordered_map>
#include <vector>

#include "cutting/weld_map.h"
#include "engine/geometry/tet_extent.h"
#include "engine/mesh_quality.h"
#include "engine/tet_faces.h"

namespace serosa::cutting {
namespace {

// Faces of a tet as local node triples.

struct NodeInfo {
  double phi = 0.0;                 ///< signed distance to the plane, m
  int sign = 0;                     ///< +1, 0, -1 within tol
  std::vector<std::int32_t> star;   ///< candidate indices of the tets around it
  std::vector<std::int32_t> cross;  ///< crossing-edge indices at it
  bool moved = false;
  Vec3 rest, x;             ///< moved: new rest and current positions
  std::int32_t other = -1;  ///< moved: the edge's other end
  double s = 0.0;           ///< moved: parameter from this node to `other`
  bool split = false;
  std::int8_t boundary = -1;       ///< -1 unknown, 0 interior, 1 on the boundary
  std::vector<std::int32_t> bnbr;  ///< boundary: the other ends of its boundary edges
  std::vector<std::array<std::int32_t, 2>> bfaces;  ///< boundary faces at it: the other two
};

struct Crossing {
  std::int32_t a = -1, b = -1;  ///< a < b
  double t = 0.0;               ///< crossing parameter from a to b
};

enum class Side { kNeg, kPos, kStraddle };

class Snapper {
 public:
  Snapper(const TetMesh& mesh, const ConvexPolygon& blade, const SnapOptions& options,
          const TetBoxQuery& query)
      : m_mesh(mesh), m_blade(blade), m_options(options), m_query(query) {}

  CutResult run(SnapStats& snap) {
    if (!find_candidates()) return std::move(m_result);
    classify();
    snap.crossing_edges = static_cast<std::int64_t>(m_cross.size());
    snap_nodes(snap);
    separate(snap);
    emit(snap);
    return std::move(m_result);
  }

 private:
  double max_edge(const std::vector<std::int32_t>& tets) const {
    return geometry::longest_edge_m(m_mesh, tets);
  }

  // Candidates: every tet around every node a move or a split may touch. A moved node ends a
  // crossing edge (length <= h) whose crossing point is within tol of the blade's box, so its
  // tets all meet the box grown by h + 2 tol; h grows until it bounds the edges found.
  bool find_candidates() {
    std::vector<std::int32_t> first;
    m_query(m_blade.box_min(), m_blade.box_max(), first);
    if (first.empty()) return false;
    double h = max_edge(first);
    for (int iter = 0; iter < 4; ++iter) {
      m_tol = m_options.classify_rel * h;
      const Vec3 grow = Vec3::Constant(h + 2.0 * m_tol);
      m_cands.clear();
      m_query(m_blade.box_min() - grow, m_blade.box_max() + grow, m_cands);
      std::sort(m_cands.begin(), m_cands.end());
      m_cands.erase(std::unique(m_cands.begin(), m_cands.end()), m_cands.end());
      const double h2 = max_edge(m_cands);
      if (h2 <= h) break;
      h = h2;
    }
    m_result.stats.tolerance_m = m_tol;
    m_result.stats.candidates = static_cast<std::int64_t>(m_cands.size());
    return !m_cands.empty();
  }

  NodeInfo& node(std::int32_t id) {
    auto [it, fresh] = m_nodes.try_emplace(id);
    if (fresh) {
      it->second.phi = m_blade.signed_distance(m_mesh.x[id]);
      it->second.sign = it->second.phi > m_tol ? 1 : it->second.phi < -m_tol ? -1 : 0;
    }
    return it->second;
  }

  // Node signs, stars, crossing edges inside the polygon.
  void classify() {
    std::unordered_map<std::uint64_t, bool> seen;
    for (std::size_t ci = 0; ci < m_cands.size(); ++ci) {
      const Tet& t = m_mesh.tets[static_cast<std::size_t>(m_cands[ci])];
      for (int k = 0; k < 4; ++k) node(t[k]).star.push_back(static_cast<std::int32_t>(ci));
      for (int i = 0; i < 4; ++i)
        for (int j = i + 1; j < 4; ++j) {
          NodeInfo& ni = m_nodes[t[i]];
          NodeInfo& nj = m_nodes[t[j]];
          if (ni.sign * nj.sign >= 0) continue;
          if (!seen.try_emplace(edge_key(t[i], t[j]), true).second) continue;
          Crossing c{std::min(t[i], t[j]), std::max(t[i], t[j]), 0.0};
          const double pa = m_nodes[c.a].phi, pb = m_nodes[c.b].phi;
          c.t = pa / (pa - pb);
          const Vec3 p = m_mesh.x[c.a] + c.t * (m_mesh.x[c.b] - m_mesh.x[c.a]);
          if (m_blade.inside_margin(p) < -m_tol) continue;
          const auto idx = static_cast<std::int32_t>(m_cross.size());
          m_cross.push_back(c);
          m_nodes[c.a].cross.push_back(idx);
          m_nodes[c.b].cross.push_back(idx);
        }
    }
  }

  // Is node n on the boundary (a face of its star used by one tet)? Fills its boundary edges
  // (the other ends). Its star is complete.
  bool on_boundary(std::int32_t n) {
    NodeInfo& info = m_nodes[n];
    if (info.boundary >= 0) return info.boundary == 1;
    std::unordered_map<std::uint64_t, int> count;  // faces at n, keyed by their other two nodes
    for (std::int32_t ci : info.star) {
      const Tet& t = m_mesh.tets[static_cast<std::size_t>(m_cands[static_cast<std::size_t>(ci)])];
      for (const auto& f : kTetFaces) {
        std::array<std::int32_t, 2> o{};
        int r = 0;
        bool has = false;
        for (int k : f) {
          if (t[k] == n) {
            has = true;
          } else if (r < 2) {
            o[static_cast<std::size_t>(r++)] = t[k];
          }
        }
        if (has) ++count[edge_key(o[0], o[1])];
      }
    }
    info.boundary = 0;
    for (const auto& [k, c] : count) {
      if (c != 1) continue;
      info.boundary = 1;
      info.bnbr.push_back(static_cast<std::int32_t>(k >> 32));
      info.bnbr.push_back(static_cast<std::int32_t>(k & 0xffffffffu));
      info.bfaces.push_back(
          {static_cast<std::int32_t>(k >> 32), static_cast<std::int32_t>(k & 0xffffffffu)});
    }
    return info.boundary == 1;
  }

  // Is edge (n, m) on the boundary (in a boundary face at n)? After on_boundary(n).
  bool boundary_edge(std::int32_t n, std::int32_t m) const {
    const std::vector<std::int32_t>& b = m_nodes.at(n).bnbr;
    return std::find(b.begin(), b.end(), m) != b.end();
  }

  [[nodiscard]] const Vec3& rest_of(std::int32_t id) const {
    const auto it = m_nodes.find(id);
    return it != m_nodes.end() && it->second.moved ? it->second.rest : m_mesh.rest[id];
  }
  [[nodiscard]] const Vec3& x_of(std::int32_t id) const {
    const auto it = m_nodes.find(id);
    return it != m_nodes.end() && it->second.moved ? it->second.x : m_mesh.x[id];
  }

  // Still crossing: neither end moved.
  [[nodiscard]] bool unresolved(const Crossing& c) const {
    return !m_nodes.at(c.a).moved && !m_nodes.at(c.b).moved;
  }

  // Does moving boundary node n towards m keep every boundary face at n in its plane (the old
  // surface unchanged)? After on_boundary(n).
  bool tangent(std::int32_t n, std::int32_t m) const {
    const Vec3 d = m_mesh.x[m] - m_mesh.x[n];
    for (const auto& f : m_nodes.at(n).bfaces) {
      const Vec3 nf = (m_mesh.x[f[0]] - m_mesh.x[n]).cross(m_mesh.x[f[1]] - m_mesh.x[n]);
      if (std::abs(nf.dot(d)) > 1e-9 * nf.norm() * d.norm()) return false;
    }
    return true;
  }

  // Tries to slide node n onto the plane when one of its crossing edges still crosses: along
  // the crossing edge with the shortest move (any of n's crossing edges, resolved or not: the
  // target is the crossing point of the original edge, whose parents are old nodes). A boundary
  // node moves only along boundary edges, and only tangentially (keeping every surface face at n
  // in its plane) unless `any_boundary_edge`.
  bool try_snap(std::int32_t n, bool any_boundary_edge, SnapStats& snap) {
    NodeInfo& info = m_nodes[n];
    if (info.moved) return true;
    bool needed = false;
    for (std::int32_t ei : info.cross)
      needed = needed || unresolved(m_cross[static_cast<std::size_t>(ei)]);
    if (!needed) return false;
    const bool fixed = static_cast<std::size_t>(n) < m_mesh.fixed.size() && m_mesh.fixed[n] != 0;
    const bool boundary = on_boundary(n);
    std::int32_t best = -1;
    double best_len = 0.0;
    for (std::int32_t ei : info.cross) {
      const Crossing& c = m_cross[static_cast<std::size_t>(ei)];
      const std::int32_t m = c.a == n ? c.b : c.a;
      if (boundary && !boundary_edge(n, m)) continue;
      if (boundary && !any_boundary_edge && !tangent(n, m)) continue;
      const double s = c.a == n ? c.t : 1.0 - c.t;
      const double len = s * (m_mesh.x[m] - m_mesh.x[n]).norm();
      if (best < 0 || len < best_len) {
        best = ei;
        best_len = len;
      }
    }
    if (best < 0) return false;
    if (fixed) {
      ++snap.snaps_refused;
      return false;
    }
    const Crossing& c = m_cross[static_cast<std::size_t>(best)];
    const std::int32_t m = c.a == n ? c.b : c.a;
    const double s = c.a == n ? c.t : 1.0 - c.t;
    const Vec3 rest = (1.0 - s) * m_mesh.rest[n] + s * m_mesh.rest[m];
    const Vec3 x = (1.0 - s) * m_mesh.x[n] + s * m_mesh.x[m];
    // The quality floor around n, rest and current.
    for (std::int32_t ci : info.star) {
      const Tet& t = m_mesh.tets[static_cast<std::size_t>(m_cands[static_cast<std::size_t>(ci)])];
      std::array<Vec3, 4> r{}, p{}, r2{}, p2{};
      for (std::size_t k = 0; k < 4; ++k) {
        r[k] = r2[k] = rest_of(t[k]);
        p[k] = p2[k] = x_of(t[k]);
        if (t[k] == n) {
          r2[k] = rest;
          p2[k] = x;
        }
      }
      const double qr = tet_quality(r[0], r[1], r[2], r[3]);
      const double qp = tet_quality(p[0], p[1], p[2], p[3]);
      const double qr2 = tet_quality(r2[0], r2[1], r2[2], r2[3]);
      const double qp2 = tet_quality(p2[0], p2[1], p2[2], p2[3]);
      const double floor_r = std::min(m_options.min_quality, qr);
      const double floor_p = std::min(m_options.min_quality, qp);
      if (!(qr2 > 0.0 && qp2 > 0.0 && qr2 >= floor_r && qp2 >= floor_p)) {
        ++snap.snaps_refused;
        return false;
      }
    }
    info.moved = true;
    info.rest = rest;
    info.x = x;
    info.other = m;
    info.s = s;
    ++snap.nodes_snapped;
    snap.max_move_m = std::max(snap.max_move_m, best_len);
    return true;
  }

  // One greedy snapping attempt. Pass 1 moves, nearest the plane first, for each crossing edge
  // the endpoint `strategy` picks: 0 the nearer one (ties: the positive one), 1 the negative one,
  // 2 the positive one. Pass 2: edges still crossing try both ends again (neighbours may have
  // moved meanwhile); pass 3 lets boundary nodes leave their surface planes (along a boundary
  // edge).
  void attempt(int strategy, SnapStats& snap) {
    std::vector<std::int32_t> first;
    for (const Crossing& c : m_cross) {
      const double pa = std::abs(m_nodes[c.a].phi), pb = std::abs(m_nodes[c.b].phi);
      const bool a_pos = m_nodes[c.a].sign > 0;
      const bool take_a = strategy == 0   ? pa < pb || (pa == pb && a_pos)
                          : strategy == 1 ? !a_pos
                                          : a_pos;
      first.push_back(take_a ? c.a : c.b);
    }
    std::sort(first.begin(), first.end(), [&](std::int32_t a, std::int32_t b) {
      const double pa = std::abs(m_nodes[a].phi), pb = std::abs(m_nodes[b].phi);
      return pa < pb || (pa == pb && a < b);
    });
    first.erase(std::unique(first.begin(), first.end()), first.end());
    for (std::int32_t n : first) try_snap(n, false, snap);
    for (const bool any_edge : {false, true})
      for (const Crossing& c : m_cross) {
        if (!unresolved(c)) continue;
        const bool a_first = std::abs(m_nodes[c.a].phi) <= std::abs(m_nodes[c.b].phi);
        if (!try_snap(a_first ? c.a : c.b, any_edge, snap) || unresolved(c))
          try_snap(a_first ? c.b : c.a, any_edge, snap);
      }
    for (const Crossing& c : m_cross) snap.edges_unresolved += unresolved(c) ? 1 : 0;
  }

  // A greedy choice can leave an edge whose two ends each close a tet whose three other nodes
  // already lie on the plane (moving either would flatten it). The three attempts meet that in
  // different places; the one leaving the fewest crossing edges wins (then the fewest moves).
  void snap_nodes(SnapStats& snap) {
    std::vector<std::int32_t> ids;
    for (const Crossing& c : m_cross) {
      ids.push_back(c.a);
      ids.push_back(c.b);
    }
    std::sort(ids.begin(), ids.end());
    ids.erase(std::unique(ids.begin(), ids.end()), ids.end());
    auto reset = [&] {
      for (std::int32_t id : ids) m_nodes[id].moved = false;
    };
    int best = -1;
    SnapStats best_stats;
    for (int strategy = 0; strategy < 3; ++strategy) {
      reset();
      SnapStats st = snap;
      attempt(strategy, st);
      if (best < 0 || st.edges_unresolved < best_stats.edges_unresolved ||
          (st.edges_unresolved == best_stats.edges_unresolved &&
           st.nodes_snapped < best_stats.nodes_snapped)) {
        best = strategy;
        best_stats = st;
      }
      if (best_stats.edges_unresolved == 0 && strategy == 0) break;  // the nearest-first wins
    }
    if (best != 2) {  // the state holds the last attempt's moves: redo the best
      reset();
      SnapStats st = snap;
      attempt(best, st);
    }
    snap = best_stats;
  }

  [[nodiscard]] int sign_after(std::int32_t id) const {
    const NodeInfo& n = m_nodes.at(id);
    return n.moved ? 0 : n.sign;
  }

  [[nodiscard]] Side side(std::int32_t ci) const {
    const Tet& t = m_mesh.tets[static_cast<std::size_t>(m_cands[static_cast<std::size_t>(ci)])];
    bool pos = false, neg = false;
    for (std::int32_t id : t) {
      pos = pos || sign_after(id) > 0;
      neg = neg || sign_after(id) < 0;
    }
    return pos && neg ? Side::kStraddle : pos ? Side::kPos : Side::kNeg;
  }

  // Nodes on the plane inside the polygon, with tets on both sides and none straddling, split.
  void separate(SnapStats& snap) {
    for (auto& [id, info] : m_nodes) {
      if (sign_after(id) != 0) continue;
      if (!info.moved && m_blade.inside_margin(m_mesh.x[id]) < -m_tol) continue;
      bool pos = false, neg = false, straddle = false;
      for (std::int32_t ci : info.star) {
        const Side s = side(ci);
        pos = pos || s == Side::kPos;
        neg = neg || s == Side::kNeg;
        straddle = straddle || s == Side::kStraddle;
      }
      info.split = pos && neg && !straddle;
      snap.nodes_split += info.split ? 1 : 0;
    }
  }

  void emit(SnapStats& snap) {
    (void)snap;
    TopologyDelta& d = m_result.delta;
    // New node ids in ascending order of the node they replace.
    std::vector<std::int32_t> ids;
    for (const auto& [id, info] : m_nodes)
      if (info.moved || info.split) ids.push_back(id);
    std::sort(ids.begin(), ids.end());
    std::unordered_map<std::int32_t, std::array<std::int32_t, 2>> copy;  // node -> {neg, pos}
    std::int32_t next = m_mesh.num_nodes();
    for (std::int32_t id : ids) {
      const NodeInfo& info = m_nodes.at(id);
      NodeParent p;
      if (info.moved) {
        p.count = 2;
        p.nodes = {id, info.other, -1, -1};
        p.weights = {1.0 - info.s, info.s, 0.0, 0.0};
      } else {
        p.count = 1;
        p.nodes = {id, -1, -1, -1};
        p.weights = {1.0, 0.0, 0.0, 0.0};
      }
      std::array<std::int32_t, 2> c{id, id};
      if (info.moved) {
        c[0] = next++;
        d.added_nodes.push_back(p);
      }
      if (info.split) {
        c[1] = next++;
        d.added_nodes.push_back(p);
      } else {
        c[1] = c[0];
      }
      copy[id] = c;
    }
    m_result.stats.clones = snap.nodes_split;
    // Tets to re-emit: around moved nodes, and positive tets around split nodes.
    std::vector<std::int32_t> touched;
    for (std::size_t ci = 0; ci < m_cands.size(); ++ci) {
      const Tet& t = m_mesh.tets[static_cast<std::size_t>(m_cands[ci])];
      const Side s = side(static_cast<std::int32_t>(ci));
      bool hit = false;
      for (std::int32_t id : t) {
        const NodeInfo& info = m_nodes.at(id);
        hit = hit || info.moved || (info.split && s == Side::kPos);
      }
      if (hit) touched.push_back(static_cast<std::int32_t>(ci));
    }
    for (std::int32_t ci : touched) {  // candidates are sorted, so tet ids come out sorted
      const std::int32_t ti = m_cands[static_cast<std::size_t>(ci)];
      const Tet& t = m_mesh.tets[static_cast<std::size_t>(ti)];
      const bool pos = side(ci) == Side::kPos;
      Tet out = t;
      for (std::size_t k = 0; k < 4; ++k)
        if (const auto it = copy.find(t[k]); it != copy.end()) out[k] = it->second[pos ? 1 : 0];
      d.removed_tets.push_back(ti);
      d.added_tets.push_back(out);
      d.added_groups.push_back(m_mesh.group[static_cast<std::size_t>(ti)]);
      const double v = signed_volume(rest_of(t[0]), rest_of(t[1]), rest_of(t[2]), rest_of(t[3]));
      if (!(v > 0.0)) ++m_result.stats.degenerate_tets;
    }
    m_result.stats.tets_removed = static_cast<std::int64_t>(d.removed_tets.size());
    m_result.stats.tets_added = static_cast<std::int64_t>(d.added_tets.size());
    m_result.stats.nodes_added = static_cast<std::int64_t>(d.added_nodes.size());
  }

  const TetMesh& m_mesh;
  const ConvexPolygon& m_blade;
  SnapOptions m_options;
  const TetBoxQuery& m_query;
  double m_tol = 0.0;
  std::vector<std::int32_t> m_cands;  ///< sorted candidate tet ids
  std::unordered_map<std::int32_t, NodeInfo> m_nodes;
  std::vector<Crossing> m_cross;
  CutResult m_result;
};

}  // namespace

CutResult snap_cut(const TetMesh& mesh, const ConvexPolygon& blade, const SnapOptions& options,
                   const TetBoxQuery& query, SnapStats* snap) {
  const TetBoxQuery q = query ? query : brute_force_query(mesh);
  SnapStats local;
  Snapper s(mesh, blade, options, q);
  CutResult r = s.run(local);
  if (snap != nullptr) *snap = local;
  return r;
}

}  // namespace serosa::cutting
