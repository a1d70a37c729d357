// cut_mesh: the paper's pattern-based scissor cut.
//
// Design note (the paper's figures are missing; this is what the code does and why)
// ------------------------------------------------------------------------------
// 1. Classification. Each node of a candidate tet gets phi = n . x - d against the blade's plane
//    and a sign +, 0 or - with the tolerance tol = classify_rel * h, h the longest edge of the
//    tets whose boxes meet the blade's box. The sign is a property of the node (computed once
//    per cut), never of a tet, so every tet sharing a node agrees on it. A tet's four signs give
//    one of 3^4 = 81 codes.
// 2. Case table (cutting/case_table.h). Every code maps to one of the paper's seven canonical
//    cases, plus "untouched" (+,+,+,+) and "degenerate" (0,0,0,0), through an EVEN permutation
//    of the tet's nodes (so the canonical tet keeps the positive orientation) and a mirror flag
//    (swap + and -). An even permutation always exists: four nodes and three signs means two
//    nodes share a sign, and swapping them fixes the parity.
//        kOneThree     (+,-,-,-)  tet (0, e01, e02, e03) | prism (1,2,3 / e01,e02,e03)
//        kTwoTwo       (+,+,-,-)  prism (0,e02,e03 / 1,e12,e13) | prism (2,e02,e12 / 3,e03,e13)
//        kOneZeroSplit (0,+,-,-)  tet (0, 1, e12, e13) | pyramid (2, 3, e13, e12; apex 0)
//        kTwoZeroSplit (0,0,+,-)  tet (0, 1, 2, e23) | tet (0, 1, e23, 3)
//        kOneZeroSame, kTwoZeroSame, kThreeZero: the tet whole (the "clipping" cases: only the
//        coplanar nodes inside the polygon change, to their clones on the positive side)
//    (eij: the cut point on canonical edge i-j; left of "|" the positive side, right the
//    negative; a mirrored case swaps the sides.) Pieces are exactly the tet cut by the plane of
//    the linearly interpolated phi, so they are convex and cover the tet without overlap: volume
//    is conserved to rounding and, since cut points sit strictly inside edges (|phi| > tol at
//    both ends), every piece has positive volume.
// 3. Primitives to tets (cutting/subdivide.h): prisms and pyramids use paper Tables 1 and 2 with
//    the Figure 9 selectors: every quad is cut by its diagonal through the smallest node id.
//    Every quad lies in one face of the original tet (or in the cut section), and the rule
//    depends only on the quad's four ids, so both tets sharing a face cut it the same way. The
//    two Schönhardt prisms (all three diagonals turning the same way) get a Steiner point at
//    the mean of their six nodes, expressed through the original tet's four nodes.
// 4. Welding (cutting/weld_map.h): a cut edge gets two nodes at the same place, one for each
//    side, keyed by the edge, so every tet around it uses the same pair. A coplanar node inside
//    the polygon is cloned: the original stays with the negative side, the clone goes to the
//    positive side (paper convention).
// 5. Complete or partial. A crossing edge gets a cut point iff the point lies inside the polygon
//    (a property of the edge, so every tet around it agrees). A straddling tet is "complete" when
//    its whole section lies in the polygon: every crossing edge's point and every coplanar node
//    inside. The crack opens only where this is sure to stay on the blade: a cut point gets two
//    nodes iff every tet around its edge is complete (else one, welded); a coplanar node is
//    cloned iff it is inside the polygon, every straddling tet around it is complete, every
//    coplanar face around it has all three nodes inside, no flat tet holds it, and both sides
//    use it (no orphaned node). An opened face then always has all its nodes inside the polygon.
//    Complete tets use the patterns of point 2 with these (paired or welded) nodes. A straddling
//    tet that is not complete but has cut points (the polygon's boundary crosses it: the blade
//    ends inside it) is split WITHOUT opening: each face is triangulated by the same rule as the
//    patterns (cutting/subdivide.h split_face: a point joined to the opposite node, or a corner
//    triangle and a quad cut through its smallest id) and coned from a Steiner point at the
//    tet's centroid. The mesh stays welded around the crack's front.
//    Stated plainly: the crack stops at the last complete tets, up to one element short of the
//    polygon's edge. The paper's partial patterns that follow the polygon's edge inside a tet
//    (face points where the blade's edge crosses a face, a point at the blade's tip inside a
//    tet, and the "end cases" where the blade crosses a face without cutting its edges) are NOT
//    implemented; a tet the blade enters without cutting any of its edges is left whole.
// 6. Output: the touched tets (cut, or one-sided tets that take a clone) are removed, their
//    pieces added with the same group, each piece oriented positively by its rest volume.
#include "cutting/cut_mesh.h"

#include <algorithm>
#include <cmath>
#include <unordered_map>

#include "cutting/patterns.h"
#include "cutting/subdivide.h"
#include "cutting/weld_map.h"

namespace serosa::cutting {
namespace {

// Faces of a tet as local node triples.
constexpr std::array<std::array<int, 3>, 4> kFaces{{{1, 2, 3}, {0, 3, 2}, {0, 1, 3}, {0, 2, 1}}};

struct NodeInfo {
  double phi = 0.0;  ///< signed distance to the plane, m
  Sign sign = Sign::kZero;
  bool inside = false;  ///< coplanar node inside the polygon (grown by tol)
};

struct EdgeInfo {
  double t = 0.0;       ///< cut point parameter from min id to max id
  bool inside = false;  ///< cut point inside the polygon (grown by tol): the edge is split
  bool open = false;    ///< inside and every tet around it complete: two nodes
  std::vector<std::int32_t> tets;  ///< candidate indices of the tets around it
};

struct TetInfo {
  std::array<Sign, 4> sign{};
  int code = 0;
  bool straddles = false;   ///< has a + and a - node
  bool complete = false;    ///< straddles and its whole section lies in the polygon
  bool has_points = false;  ///< straddles and some crossing edge's cut point is inside
};

// A point of a piece as a combination of original nodes (the weights apply() uses).
struct Combo {
  std::array<std::int32_t, 4> nodes{-1, -1, -1, -1};
  std::array<double, 4> w{0.0, 0.0, 0.0, 0.0};
  int count = 0;
  void add(std::int32_t n, double weight) {
    for (int k = 0; k < count; ++k)
      if (nodes[k] == n) {
        w[k] += weight;
        return;
      }
    nodes[count] = n;
    w[count] = weight;
    ++count;
  }
  [[nodiscard]] Vec3 rest(const TetMesh& m) const {
    Vec3 r = Vec3::Zero();
    for (int k = 0; k < count; ++k) r += w[k] * m.rest[nodes[k]];
    return r;
  }
};

void tet_box(const TetMesh& m, const Tet& t, Vec3& lo, Vec3& hi) {
  lo = hi = m.x[t[0]];
  for (int k = 1; k < 4; ++k) {
    lo = lo.cwiseMin(m.x[t[k]]);
    hi = hi.cwiseMax(m.x[t[k]]);
  }
}

// Everything one cut needs while it builds the delta.
class Cutter {
 public:
  Cutter(const TetMesh& mesh, const ConvexPolygon& blade, const CutOptions& options,
         const TetBoxQuery& query)
      : m_mesh(mesh),
        m_blade(blade),
        m_options(options),
        m_query(query),
        m_weld(mesh.num_nodes()) {}

  CutResult run() {
    if (!find_candidates()) return std::move(m_result);
    classify();
    decide_edges();
    decide_clones();
    emit();
    return std::move(m_result);
  }

 private:
  // Candidate tets: boxes meeting the blade's box, then grown by twice the tolerance so that
  // every tet around a node or cut point within tolerance of the polygon is found.
  bool find_candidates() {
    std::vector<std::int32_t> first;
    m_query(m_blade.box_min(), m_blade.box_max(), first);
    if (first.empty()) return false;
    double h = 0.0;
    for (std::int32_t ti : first) {
      const Tet& t = m_mesh.tets[ti];
      for (int i = 0; i < 4; ++i)
        for (int j = i + 1; j < 4; ++j) h = std::max(h, (m_mesh.x[t[i]] - m_mesh.x[t[j]]).norm());
    }
    m_tol = m_options.classify_rel * h;
    m_result.stats.tolerance_m = m_tol;
    const Vec3 grow = Vec3::Constant(2.0 * m_tol);
    m_query(m_blade.box_min() - grow, m_blade.box_max() + grow, m_cands);
    std::sort(m_cands.begin(), m_cands.end());
    m_cands.erase(std::unique(m_cands.begin(), m_cands.end()), m_cands.end());
    m_result.stats.candidates = static_cast<std::int64_t>(m_cands.size());
    return !m_cands.empty();
  }

  // Signs of nodes (once per node), cases of tets, cut points of crossing edges.
  void classify() {
    CutStats& st = m_result.stats;
    m_tets.resize(m_cands.size());
    for (std::size_t ci = 0; ci < m_cands.size(); ++ci) {
      const Tet& t = m_mesh.tets[m_cands[ci]];
      TetInfo& info = m_tets[ci];
      bool pos = false, neg = false;
      for (int k = 0; k < 4; ++k) {
        const NodeInfo& n = node(t[k]);
        info.sign[k] = n.sign;
        pos = pos || n.sign == Sign::kPos;
        neg = neg || n.sign == Sign::kNeg;
        if (n.sign == Sign::kZero) m_zero_tets[t[k]].push_back(static_cast<std::int32_t>(ci));
      }
      info.code = case_code(info.sign);
      info.straddles = pos && neg;
      ++st.per_code[info.code];
      ++st.per_case[static_cast<int>(case_table()[info.code].canonical)];
      if (!info.straddles) continue;
      // Geometrically complete: every cut point and coplanar node inside the polygon.
      bool complete = true;
      for (int i = 0; i < 4; ++i) {
        if (info.sign[i] == Sign::kZero) complete = complete && m_nodes[t[i]].inside;
        for (int j = i + 1; j < 4; ++j) {
          if (static_cast<int>(info.sign[i]) * static_cast<int>(info.sign[j]) >= 0) continue;
          EdgeInfo& e = edge(t[i], t[j]);
          e.tets.push_back(static_cast<std::int32_t>(ci));
          complete = complete && e.inside;
          info.has_points = info.has_points || e.inside;
        }
      }
      info.complete = complete;
    }
  }

  const NodeInfo& node(std::int32_t id) {
    auto [it, fresh] = m_nodes.try_emplace(id);
    if (fresh) {
      NodeInfo& n = it->second;
      n.phi = m_blade.signed_distance(m_mesh.x[id]);
      n.sign = n.phi > m_tol ? Sign::kPos : n.phi < -m_tol ? Sign::kNeg : Sign::kZero;
      n.inside = n.sign == Sign::kZero && m_blade.contains_projection(m_mesh.x[id], m_tol);
    }
    return it->second;
  }

  EdgeInfo& edge(std::int32_t a, std::int32_t b) {
    auto [it, fresh] = m_edges.try_emplace(edge_key(a, b));
    if (fresh) {
      const std::int32_t lo = std::min(a, b), hi = std::max(a, b);
      const double plo = m_nodes[lo].phi, phi_hi = m_nodes[hi].phi;
      it->second.t = plo / (plo - phi_hi);
      const Vec3 p = m_mesh.x[lo] + it->second.t * (m_mesh.x[hi] - m_mesh.x[lo]);
      it->second.inside = m_blade.contains_projection(p, m_tol);
    }
    return it->second;
  }

  // A cut point opens (two nodes) iff every tet around its edge is complete.
  void decide_edges() {
    for (auto& [key, e] : m_edges) {
      e.open = e.inside;
      for (std::int32_t ci : e.tets)
        e.open = e.open && m_tets[static_cast<std::size_t>(ci)].complete;
    }
  }

  // Clones of coplanar nodes (rules in the design note, point 5), in ascending node order.
  void decide_clones() {
    std::vector<std::int32_t> zero_nodes;
    for (const auto& [id, tets] : m_zero_tets)
      if (m_nodes[id].inside) zero_nodes.push_back(id);
    std::sort(zero_nodes.begin(), zero_nodes.end());
    for (std::int32_t a : zero_nodes) {
      bool ok = true, pos_user = false, neg_user = false;
      for (std::int32_t ci : m_zero_tets[a]) {
        const TetInfo& info = m_tets[static_cast<std::size_t>(ci)];
        const Tet& t = m_mesh.tets[m_cands[static_cast<std::size_t>(ci)]];
        if (info.straddles) {
          ok = ok && info.complete;
          pos_user = neg_user = true;
          continue;
        }
        bool any = false;
        for (int k = 0; k < 4; ++k) {
          pos_user = pos_user || info.sign[k] == Sign::kPos;
          neg_user = neg_user || info.sign[k] == Sign::kNeg;
          any = any || info.sign[k] != Sign::kZero;
        }
        ok = ok && any;  // a flat tet (all four coplanar) pins its nodes
        for (const auto& f : kFaces) {
          bool has_a = false, coplanar = true, inside = true;
          for (int k : f) {
            has_a = has_a || t[k] == a;
            coplanar = coplanar && info.sign[k] == Sign::kZero;
            inside = inside && m_nodes[t[k]].inside;
          }
          if (has_a && coplanar) ok = ok && inside;
        }
      }
      if (ok && pos_user && neg_user) m_weld.clone(a);
    }
  }

  // Resolves one pattern label of tet `t` (canonical order `perm`) on side `pos`.
  std::int32_t resolve(const Tet& t, const CaseEntry& c, std::uint8_t label, bool pos,
                       Combo& combo) {
    if (!is_edge_label(label)) {
      const std::int32_t v = t[c.perm[label]];
      combo.add(v, 1.0);
      if (pos)
        if (auto cl = m_weld.find_clone(v)) return *cl;
      return v;
    }
    const auto& en = kEdgeNodes[label - 4];
    const std::int32_t a = t[c.perm[en[0]]], b = t[c.perm[en[1]]];
    const std::int32_t lo = std::min(a, b), hi = std::max(a, b);
    const EdgeInfo& e = m_edges[edge_key(a, b)];
    combo.add(lo, 1.0 - e.t);
    combo.add(hi, e.t);
    const EdgePair pair = m_weld.edge_point(a, b, e.t, e.open);
    return pos ? pair.pos : pair.neg;
  }

  void emit_tet(std::array<std::int32_t, 4> ids, std::array<Combo, 4> combos, std::uint16_t g) {
    const double vol = signed_volume(combos[0].rest(m_mesh), combos[1].rest(m_mesh),
                                     combos[2].rest(m_mesh), combos[3].rest(m_mesh));
    if (vol < 0.0) std::swap(ids[2], ids[3]);
    if (!(std::abs(vol) > 0.0)) ++m_result.stats.degenerate_tets;
    m_result.delta.added_tets.push_back({ids[0], ids[1], ids[2], ids[3]});
    m_result.delta.added_groups.push_back(g);
  }

  void emit_primitive(const Tet& t, const CaseEntry& c, const PatternPrimitive& prim,
                      std::uint16_t g) {
    const bool pos = (prim.side == Side::kPos) != c.mirrored;
    std::array<std::int32_t, 7> ids{};
    std::array<Combo, 7> combos{};
    const int n = prim.size();
    for (int k = 0; k < n; ++k) ids[k] = resolve(t, c, prim.points[k], pos, combos[k]);
    PrimitiveSplit split;
    if (prim.kind == PrimitiveKind::kTet) {
      emit_tet({ids[0], ids[1], ids[2], ids[3]}, {combos[0], combos[1], combos[2], combos[3]}, g);
      return;
    }
    if (prim.kind == PrimitiveKind::kPyramid) {
      split = split_pyramid({ids[0], ids[1], ids[2], ids[3], ids[4]});
    } else {
      split = split_prism({ids[0], ids[1], ids[2], ids[3], ids[4], ids[5]});
      if (split.steiner) {
        // Mean of the six nodes, through the original tet's nodes.
        Combo mean;
        for (int k = 0; k < 6; ++k)
          for (int j = 0; j < combos[k].count; ++j)
            mean.add(combos[k].nodes[j], combos[k].w[j] / 6.0);
        NodeParent p;
        p.count = static_cast<std::uint8_t>(mean.count);
        for (int j = 0; j < mean.count; ++j) {
          p.nodes[j] = mean.nodes[j];
          p.weights[j] = mean.w[j];
        }
        ids[6] = m_weld.add_point(p);
        combos[6] = mean;
        ++m_result.stats.steiner_points;
      }
    }
    for (const LocalTet& lt : split.tets)
      emit_tet({ids[lt[0]], ids[lt[1]], ids[lt[2]], ids[lt[3]]},
               {combos[lt[0]], combos[lt[1]], combos[lt[2]], combos[lt[3]]}, g);
  }

  // A straddling tet the polygon's boundary crosses: its faces split at the (welded) cut points
  // by split_face, coned from a Steiner point at the centroid.
  void emit_partial(const Tet& t, std::uint16_t g) {
    Combo centre;
    for (int k = 0; k < 4; ++k) centre.add(t[k], 0.25);
    NodeParent p;
    p.count = 4;
    for (int k = 0; k < 4; ++k) {
      p.nodes[k] = t[k];
      p.weights[k] = 0.25;
    }
    const std::int32_t apex = m_weld.add_point(p);
    ++m_result.stats.steiner_points;
    for (const auto& f : kFaces) {
      std::array<std::int32_t, 6> ids{t[f[0]], t[f[1]], t[f[2]], -1, -1, -1};
      std::array<Combo, 6> combos{};
      for (int k = 0; k < 3; ++k) combos[k].add(t[f[k]], 1.0);
      for (int k = 0; k < 3; ++k) {
        const std::int32_t a = t[f[k]], b = t[f[(k + 1) % 3]];
        const auto it = m_edges.find(edge_key(a, b));
        if (it == m_edges.end() || !it->second.inside) continue;
        const EdgeInfo& e = it->second;
        ids[3 + k] = m_weld.edge_point(a, b, e.t, e.open).pos;  // never open here
        combos[3 + k].add(std::min(a, b), 1.0 - e.t);
        combos[3 + k].add(std::max(a, b), e.t);
      }
      const FaceSplit fs = split_face(ids);
      for (int k = 0; k < fs.count; ++k) {
        const auto& tr = fs.tris[k];
        emit_tet({ids[tr[0]], ids[tr[1]], ids[tr[2]], apex},
                 {combos[tr[0]], combos[tr[1]], combos[tr[2]], centre}, g);
      }
    }
  }

  // Pieces of every touched tet, in ascending tet id.
  void emit() {
    CutStats& st = m_result.stats;
    TopologyDelta& d = m_result.delta;
    for (std::size_t ci = 0; ci < m_cands.size(); ++ci) {
      const TetInfo& info = m_tets[ci];
      const std::int32_t ti = m_cands[ci];
      const Tet& t = m_mesh.tets[ti];
      const CaseEntry& c = case_table()[info.code];
      if (info.straddles && !info.complete) {
        if (!info.has_points) continue;  // the blade misses its edges: left whole
        ++st.tets_partial;
        d.removed_tets.push_back(ti);
        emit_partial(t, m_mesh.group[ti]);
        continue;
      }
      if (info.straddles) {
        ++st.tets_split;
      } else {
        // One-sided: touched when on the positive side with a cloned coplanar node.
        bool pos = false, cloned = false;
        for (int k = 0; k < 4; ++k) {
          pos = pos || info.sign[k] == Sign::kPos;
          cloned = cloned || (info.sign[k] == Sign::kZero && m_weld.find_clone(t[k]));
        }
        if (!pos || !cloned) continue;
        ++st.tets_relabelled;
      }
      ++st.split_per_case[static_cast<int>(c.canonical)];
      d.removed_tets.push_back(ti);
      for (const PatternPrimitive& prim : pattern(c.canonical))
        emit_primitive(t, c, prim, m_mesh.group[ti]);
    }
    st.tets_removed = static_cast<std::int64_t>(d.removed_tets.size());
    st.tets_added = static_cast<std::int64_t>(d.added_tets.size());
    st.edge_pairs = m_weld.edge_pairs();
    st.edge_singles = m_weld.edge_singles();
    st.clones = m_weld.clones();
    d.added_nodes = m_weld.take_new_nodes();
    st.nodes_added = static_cast<std::int64_t>(d.added_nodes.size());
  }

  const TetMesh& m_mesh;
  const ConvexPolygon& m_blade;
  const CutOptions& m_options;
  const TetBoxQuery& m_query;
  WeldMap m_weld;
  CutResult m_result;
  double m_tol = 0.0;
  std::vector<std::int32_t> m_cands;  ///< candidate tet ids, ascending
  std::vector<TetInfo> m_tets;        ///< per candidate
  std::unordered_map<std::int32_t, NodeInfo> m_nodes;
  std::unordered_map<std::uint64_t, EdgeInfo> m_edges;  ///< crossing edges of straddling tets
  std::unordered_map<std::int32_t, std::vector<std::int32_t>>
      m_zero_tets;  ///< coplanar node -> tets
};

}  // namespace

TetBoxQuery brute_force_query(const TetMesh& mesh) {
  return [&mesh](const Vec3& lo, const Vec3& hi, std::vector<std::int32_t>& out) {
    for (std::int32_t i = 0; i < mesh.num_tets(); ++i) {
      Vec3 tlo, thi;
      tet_box(mesh, mesh.tets[i], tlo, thi);
      if ((tlo.array() <= hi.array()).all() && (thi.array() >= lo.array()).all()) out.push_back(i);
    }
  };
}

CutResult cut_mesh(const TetMesh& mesh, const ConvexPolygon& blade, const CutOptions& options,
                   const TetBoxQuery& query) {
  const TetBoxQuery brute = query ? TetBoxQuery{} : brute_force_query(mesh);
  return Cutter(mesh, blade, options, query ? query : brute).run();
}

}  // namespace serosa::cutting
