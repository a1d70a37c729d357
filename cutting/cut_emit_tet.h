// The cut's two output primitives (docs/cutting.md, point 6), shared by every kind of piece
// (patterns, partial cones, coplanar splits): the node of an edge's cut point, and one piece.
#pragma once

#include <array>
#include <cstdint>

#include "cutting/cut_state.h"

namespace serosa::cutting::detail {

/// The node(s) of the cut point on crossing edge (a, b): the id on side pos (the same on both
/// sides when the edge is welded). Adds the point's parents to combo.
std::int32_t edge_point_id(CutState& cs, std::int32_t a, std::int32_t b, bool pos, Combo& combo);

/// Adds tet `ids` (points `combos`, in group g) to the delta, swapping two nodes when its rest
/// volume is negative; counts it as degenerate when the volume is zero.
void emit_tet(CutState& cs, std::array<std::int32_t, 4> ids,
              const std::array<const Combo*, 4>& combos, std::uint16_t g);

}  // namespace serosa::cutting::detail
