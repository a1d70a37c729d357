// The cut's output (docs/cutting.md, points 2, 3 and 6): every touched tet is removed and its
// pieces added with the same group, each oriented positively by its rest volume. Complete and
// relabelled tets take their case's pattern (cutting/patterns.h, cutting/subdivide.h); partial
// tets are coned from their apex (cutting/cut_emit_partial.h); one-sided tets around clipped
// coplanar faces are split there (cutting/cut_coplanar.h).
#pragma once

#include "cutting/cut_state.h"

namespace serosa::cutting::detail {

/// The node(s) of the cut point on crossing edge (a, b): the id on side pos (the same on both
/// sides when the edge is welded). Adds the point's parents to combo.
std::int32_t edge_point_id(CutState& cs, std::int32_t a, std::int32_t b, bool pos, Combo& combo);

/// Adds tet `ids` (points `combos`, in group g) to the delta, swapping two nodes when its rest
/// volume is negative; counts it as degenerate when the volume is zero.
void emit_tet(CutState& cs, std::array<std::int32_t, 4> ids,
              const std::array<const Combo*, 4>& combos, std::uint16_t g);

/// Pieces of every touched tet, in ascending tet id, and the delta's node list and counts.
/// After decide_edges and decide_clones.
void emit(CutState& cs);

}  // namespace serosa::cutting::detail
