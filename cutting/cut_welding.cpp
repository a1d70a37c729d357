// Opening or welding the cut's edges and coplanar nodes (docs/cutting.md, points 4 and 5).
#include "cutting/cut_welding.h"

#include "cutting/cut_coplanar.h"
#include "cutting/cut_partial.h"

namespace serosa::cutting::detail {
namespace {

// Partial tet t with coplanar node a: both sides of its section from a start inside the
// blade (the midpoint of a and the next point along the side: a face point, a crossing of a
// coplanar edge or the side's other end), so opening a opens only the part of the section the
// blade covers.
bool sides_start_inside(const CutState& cs, const Tet& t, const TetInfo& info, std::int32_t a) {
  const std::vector<SecVert> sv = section(cs, t, info);
  const std::size_t ns = sv.size();
  const std::uint64_t label = edge_key(a, a);
  std::size_t i = ns;
  for (std::size_t k = 0; k < ns; ++k)
    if (sv[k].label == label) i = k;
  if (i == ns || ns < 3) return false;
  const Vec3 xa = cs.mesh.x[a];
  for (const SecVert* u : {&sv[(i + 1) % ns], &sv[(i + ns - 1) % ns]}) {
    const auto key = face_key_of(sv[i], *u);
    if (key[0] == -2) return false;
    Vec3 next = u->combo.cur(cs.mesh);
    if (key[0] == -1 && has_cop_points(cs, a, u->support[0])) {  // along a coplanar edge
      const auto& pts = cs.cop_edges.at(edge_key(a, u->support[0]));
      next = (a < u->support[0] ? pts.front() : pts.back()).combo.cur(cs.mesh);
    }
    if (key[0] >= 0) {
      const auto it = cs.faces.find(key);
      if (it != cs.faces.end() && !it->second.points.empty()) {
        const FacePoint& fp =
            label < u->label ? it->second.points.front() : it->second.points.back();
        next = fp.combo.cur(cs.mesh);
      }
    }
    if (cs.blade.inside_margin(0.5 * (xa + next)) < -cs.tol) return false;
  }
  return true;
}

// One-sided tet t lets its coplanar node a open: it is not flat (all four coplanar), and every
// coplanar face around a that is still welded lies inside the blade or is clipped along the
// blade's outline (decide_faces) with its corner at a under the blade; faces already open stay
// open.
bool one_sided_tet_lets_open(const CutState& cs, const Tet& t, const TetInfo& info,
                             std::int32_t a) {
  bool flat = true;
  for (int k = 0; k < 4; ++k) flat = flat && info.sign[k] == Sign::kZero;
  if (flat) return false;
  for (const auto& f : kTetFaces) {
    bool has_a = false, inside = true;
    for (int k : f) {
      has_a = has_a || t[k] == a;
      inside = inside && cs.nodes.at(t[k]).inside;
    }
    if (!has_a || !coplanar_face(info, f) || inside) continue;
    const FaceKey key = face_key(t, f);
    const auto count = cs.coplanar.find(key);
    const bool welded = count != cs.coplanar.end() && count->second >= 2;
    if (welded && !(cs.pfaces.count(key) > 0 && corner_inside(cs, a, key))) return false;
  }
  return true;
}

// Tet t (candidate info) around coplanar node a lets a open. A straddling tet: when complete
// (opened by its pattern), or when partial and both its section sides from a start inside the
// blade (a node on the outline whose far side an earlier cut already opened: a scissors' crack
// front); never when pinned.
bool tet_lets_open(const CutState& cs, const Tet& t, const TetInfo& info, std::int32_t a) {
  if (!info.straddles) return one_sided_tet_lets_open(cs, t, info, a);
  return !info.pinned && (info.complete || (info.interacts && sides_start_inside(cs, t, info, a)));
}

// Coplanar node a (inside the grown polygon) is cloned: every tet around it lets it open, and
// tets on both sides use it.
bool may_clone(const CutState& cs, std::int32_t a) {
  bool pos_user = false, neg_user = false;
  for (std::int32_t ci : cs.zero_tets.at(a)) {
    const TetInfo& info = cs.tets[static_cast<std::size_t>(ci)];
    const Tet& t = cs.mesh.tets[cs.cands[static_cast<std::size_t>(ci)]];
    if (!tet_lets_open(cs, t, info, a)) return false;
    for (int k = 0; k < 4; ++k) {
      pos_user = pos_user || info.sign[k] == Sign::kPos;
      neg_user = neg_user || info.sign[k] == Sign::kNeg;
    }
  }
  return pos_user && neg_user;
}

}  // namespace

void decide_edges(CutState& cs) {
  for (auto& [key, e] : cs.edges) {
    e.open = e.strict;
    for (std::int32_t ci : e.tets) e.open = e.open && !cs.tets[static_cast<std::size_t>(ci)].pinned;
  }
}

void decide_clones(CutState& cs) {
  std::vector<std::int32_t> zero_nodes;
  for (const auto& [id, tets] : cs.zero_tets)
    if (cs.nodes.at(id).inside) zero_nodes.push_back(id);
  std::sort(zero_nodes.begin(), zero_nodes.end());
  for (std::int32_t a : zero_nodes)
    if (may_clone(cs, a)) {
      cs.weld.clone(a);
      if (!cs.nodes.at(a).strict) ++cs.result.stats.clones_on_outline;
    }
}

}  // namespace serosa::cutting::detail
