// Piece emission (docs/cutting.md, points 2, 3 and 6): which tets the cut touches, and the
// pattern pieces of complete and relabelled tets.
#include "cutting/cut_emit.h"

#include "cutting/cut_coplanar.h"
#include "cutting/cut_emit_partial.h"
#include "cutting/cut_emit_tet.h"
#include "cutting/cut_partial.h"
#include "cutting/patterns.h"
#include "cutting/subdivide.h"

namespace serosa::cutting::detail {
namespace {

// Resolves one pattern label of tet `t` (canonical order c.perm) on side `pos`: a node (its
// clone on the positive side) or an edge's cut point. Adds the point's parents to combo.
std::int32_t resolve(CutState& cs, const Tet& t, const CaseEntry& c, std::uint8_t label, bool pos,
                     Combo& combo) {
  if (!is_edge_label(label)) {
    const std::int32_t v = t[c.perm[label]];
    combo.add(v, 1.0);
    return node_id(cs, v, pos);
  }
  const auto& en = kEdgeNodes[label - 4];
  return edge_point_id(cs, t[c.perm[en[0]]], t[c.perm[en[1]]], pos, combo);
}

// The tets of one pattern primitive (tet, pyramid or prism) of tet t in case c: pyramids and
// prisms are split by the paper's tables; a Schönhardt prism gets a Steiner point at the mean of
// its six nodes.
void emit_primitive(CutState& cs, const Tet& t, const CaseEntry& c, const PatternPrimitive& prim,
                    std::uint16_t g) {
  const bool pos = (prim.side == Side::kPos) != c.mirrored;
  std::array<std::int32_t, 7> ids{};
  std::array<Combo, 7> combos{};
  const int n = prim.size();
  for (int k = 0; k < n; ++k) ids[k] = resolve(cs, t, c, prim.points[k], pos, combos[k]);
  PrimitiveSplit split;
  if (prim.kind == PrimitiveKind::kTet) {
    emit_tet(cs, {ids[0], ids[1], ids[2], ids[3]}, {&combos[0], &combos[1], &combos[2], &combos[3]},
             g);
    return;
  }
  if (prim.kind == PrimitiveKind::kPyramid) {
    split = split_pyramid({ids[0], ids[1], ids[2], ids[3], ids[4]});
  } else {
    split = split_prism({ids[0], ids[1], ids[2], ids[3], ids[4], ids[5]});
    if (split.steiner) {
      // Mean of the six nodes, through the original tet's nodes.
      Combo mean;
      for (int k = 0; k < 6; ++k) mean.add(combos[k], 1.0 / 6.0);
      ids[6] = cs.weld.add_point(mean.parent());
      combos[6] = mean;
      ++cs.result.stats.steiner_points;
    }
  }
  for (const LocalTet& lt : split.tets)
    emit_tet(cs, {ids[lt[0]], ids[lt[1]], ids[lt[2]], ids[lt[3]]},
             {&combos[lt[0]], &combos[lt[1]], &combos[lt[2]], &combos[lt[3]]}, g);
}

// A partial tet the blade meets: counted, removed, and coned from its apex.
void emit_partial_tet(CutState& cs, std::int32_t ti, const TetInfo& info) {
  CutStats& st = cs.result.stats;
  ++st.tets_partial;
  st.tets_pinned += info.pinned && !info.grazed ? 1 : 0;
  st.tets_grazed += info.grazed ? 1 : 0;
  st.pinned_centred += info.pinned && info.has_centre ? 1 : 0;
  st.tets_short += !info.pinned && crack_short(cs, info) ? 1 : 0;
  cs.result.delta.removed_tets.push_back(ti);
  emit_partial(cs, cs.mesh.tets[ti], info, cs.mesh.group[ti]);
}

// What happens to a one-sided tet.
enum class OneSided {
  kUntouched,  ///< left whole
  kCopSplit,   ///< split at a clipped coplanar face or a coplanar edge with crossings
  kRelabel,    ///< on the positive side with a cloned coplanar node: takes the clone
};

OneSided one_sided_fate(const CutState& cs, const Tet& t, const TetInfo& info) {
  bool pos = false, cloned = false, flat = true;
  for (int k = 0; k < 4; ++k) {
    pos = pos || info.sign[k] == Sign::kPos;
    flat = flat && info.sign[k] == Sign::kZero;
    cloned = cloned || (info.sign[k] == Sign::kZero && cs.weld.find_clone(t[k]));
  }
  if (!flat && needs_cop_split(cs, t, info)) return OneSided::kCopSplit;
  return pos && cloned ? OneSided::kRelabel : OneSided::kUntouched;
}

// The delta's new nodes and the counts over it.
void finish(CutState& cs) {
  CutStats& st = cs.result.stats;
  TopologyDelta& d = cs.result.delta;
  st.tets_removed = static_cast<std::int64_t>(d.removed_tets.size());
  st.tets_added = static_cast<std::int64_t>(d.added_tets.size());
  st.edge_pairs = cs.weld.edge_pairs();
  st.edge_singles = cs.weld.edge_singles();
  st.clones = cs.weld.clones();
  d.added_nodes = cs.weld.take_new_nodes();
  st.nodes_added = static_cast<std::int64_t>(d.added_nodes.size());
}

}  // namespace

void emit(CutState& cs) {
  CutStats& st = cs.result.stats;
  for (std::size_t ci = 0; ci < cs.cands.size(); ++ci) {
    const TetInfo& info = cs.tets[ci];
    const std::int32_t ti = cs.cands[ci];
    const Tet& t = cs.mesh.tets[ti];
    if (info.straddles && !info.complete) {
      if (info.interacts) emit_partial_tet(cs, ti, info);  // else the blade misses it: whole
      continue;
    }
    if (info.straddles) {
      ++st.tets_split;
    } else {
      const OneSided fate = one_sided_fate(cs, t, info);
      if (fate == OneSided::kUntouched) continue;
      if (fate == OneSided::kCopSplit) {
        ++st.tets_split;
        cs.result.delta.removed_tets.push_back(ti);
        emit_cop_split(cs, t, info, cs.mesh.group[ti]);
        continue;
      }
      ++st.tets_relabelled;
    }
    const CaseEntry& c = case_table()[info.code];
    ++st.split_per_case[static_cast<int>(c.canonical)];
    cs.result.delta.removed_tets.push_back(ti);
    for (const PatternPrimitive& prim : pattern(c.canonical))
      emit_primitive(cs, t, c, prim, cs.mesh.group[ti]);
  }
  finish(cs);
}

}  // namespace serosa::cutting::detail
