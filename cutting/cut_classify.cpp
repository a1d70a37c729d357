// Classification (docs/cutting.md, point 1): a sign per node, a case per tet, a cut point per
// crossing edge, each computed once and shared by every tet that holds it, so that neighbours
// agree on how their common faces are cut.
#include "cutting/cut_classify.h"

#include "cutting/cut_coplanar.h"
#include "cutting/cut_partial.h"
#include "engine/geometry/tet_extent.h"

namespace serosa::cutting::detail {
namespace {

// Node id's sign against the plane and, on the plane, whether it lies inside the polygon.
const NodeInfo& node_info(CutState& cs, std::int32_t id) {
  auto [it, fresh] = cs.nodes.try_emplace(id);
  if (fresh) {
    NodeInfo& n = it->second;
    n.phi = cs.blade.signed_distance(cs.mesh.x[id]);
    n.sign = n.phi > cs.tol ? Sign::kPos : n.phi < -cs.tol ? Sign::kNeg : Sign::kZero;
    if (n.sign == Sign::kZero) {
      n.margin = cs.blade.inside_margin(cs.mesh.x[id]);
      n.inside = n.margin >= -cs.tol;
      n.strict = n.margin > cs.tol;
    }
  }
  return it->second;
}

// The crossing edge (a, b): its cut point, linear in phi, and whether it lies inside the polygon.
EdgeInfo& edge_info(CutState& cs, std::int32_t a, std::int32_t b) {
  auto [it, fresh] = cs.edges.try_emplace(edge_key(a, b));
  if (fresh) {
    const std::int32_t lo = std::min(a, b), hi = std::max(a, b);
    const double plo = cs.nodes[lo].phi, phi_hi = cs.nodes[hi].phi;
    it->second.t = plo / (plo - phi_hi);
    const Vec3 p = cs.mesh.x[lo] + it->second.t * (cs.mesh.x[hi] - cs.mesh.x[lo]);
    const double margin = cs.blade.inside_margin(p);
    it->second.inside = margin >= -cs.tol;
    it->second.strict = margin > cs.tol;
  }
  return it->second;
}

// The signs of candidate ci's nodes, its case, whether it straddles the plane; its coplanar
// nodes remember it.
void classify_signs(CutState& cs, std::size_t ci, const Tet& t, TetInfo& info) {
  CutStats& st = cs.result.stats;
  bool pos = false, neg = false;
  for (int k = 0; k < 4; ++k) {
    const NodeInfo& n = node_info(cs, t[k]);
    info.sign[k] = n.sign;
    pos = pos || n.sign == Sign::kPos;
    neg = neg || n.sign == Sign::kNeg;
    if (n.sign == Sign::kZero) cs.zero_tets[t[k]].push_back(static_cast<std::int32_t>(ci));
  }
  info.code = case_code(info.sign);
  info.straddles = pos && neg;
  ++st.per_code[info.code];
  ++st.per_case[static_cast<int>(case_table()[info.code].canonical)];
}

// Straddling candidate ci is geometrically complete: every cut point and coplanar node inside
// the polygon. Its crossing edges remember it.
bool section_inside(CutState& cs, std::size_t ci, const Tet& t, const TetInfo& info) {
  bool complete = true;
  for (int i = 0; i < 4; ++i) {
    if (info.sign[i] == Sign::kZero) complete = complete && cs.nodes[t[i]].inside;
    for (int j = i + 1; j < 4; ++j) {
      if (!crossing_edge(info, i, j)) continue;
      EdgeInfo& e = edge_info(cs, t[i], t[j]);
      e.tets.push_back(static_cast<std::int32_t>(ci));
      complete = complete && e.inside;
    }
  }
  return complete;
}

// A partial tet whose section side lies along a coplanar edge: where the outline crosses the
// edge, the crossings become welded nodes on it (cop_edge), shared by every tet around it, and
// the crack stops there (analyse_partial). Pinned only when one end is strictly inside, the other
// outside, and no crossing lies more than tol from both.
void stop_on_coplanar_edge(CutState& cs, const Tet& t, TetInfo& info) {
  std::array<int, 2> zeros{-1, -1};
  int nz = 0;  // a straddling tet has at most two coplanar nodes
  for (int i = 0; i < 4; ++i)
    if (info.sign[i] == Sign::kZero) zeros[static_cast<std::size_t>(nz++)] = i;
  if (nz != 2) return;
  const std::int32_t a = t[zeros[0]], b = t[zeros[1]];
  const NodeInfo &na = cs.nodes[a], &nb = cs.nodes[b];
  if (na.inside && nb.inside) return;
  if (!cop_edge(cs, a, b).empty()) {
    cs.front_edges.push_back(edge_key(a, b));
  } else {
    info.pinned = na.strict || nb.strict;
  }
}

}  // namespace

bool find_candidates(CutState& cs) {
  std::vector<std::int32_t> first;
  cs.query(cs.blade.box_min(), cs.blade.box_max(), first);
  if (first.empty()) return false;
  const double h = geometry::longest_edge_m(cs.mesh, first);
  cs.tol = cs.fixed_tol > 0.0 ? cs.fixed_tol : cs.options.classify_rel * h;
  cs.result.stats.tolerance_m = cs.tol;
  const Vec3 grow = Vec3::Constant(2.0 * cs.tol);
  cs.query(cs.blade.box_min() - grow, cs.blade.box_max() + grow, cs.cands);
  std::sort(cs.cands.begin(), cs.cands.end());
  cs.cands.erase(std::unique(cs.cands.begin(), cs.cands.end()), cs.cands.end());
  cs.result.stats.candidates = static_cast<std::int64_t>(cs.cands.size());
  return !cs.cands.empty();
}

void classify(CutState& cs) {
  cs.tets.resize(cs.cands.size());
  for (std::size_t ci = 0; ci < cs.cands.size(); ++ci) {
    const Tet& t = cs.mesh.tets[cs.cands[ci]];
    TetInfo& info = cs.tets[ci];
    classify_signs(cs, ci, t, info);
    if (!info.straddles) continue;
    info.complete = section_inside(cs, ci, t, info);
    if (info.complete) continue;
    stop_on_coplanar_edge(cs, t, info);
    analyse_partial(cs, t, info);
  }
}

}  // namespace serosa::cutting::detail
