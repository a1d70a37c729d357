// The cut's output (docs/cutting.md, points 2, 3 and 6): every touched tet is removed and its
// pieces added with the same group, each oriented positively by its rest volume. Complete and
// relabelled tets take their case's pattern (cutting/patterns.h, cutting/subdivide.h); partial
// tets are coned from their apex (cutting/cut_emit_partial.h); one-sided tets around clipped
// coplanar faces are split there (cutting/cut_coplanar.h).
#pragma once

#include "cutting/cut_state.h"

namespace serosa::cutting::detail {

/// Pieces of every touched tet, in ascending tet id, and the delta's node list and counts.
/// After decide_edges and decide_clones.
void emit(CutState& cs);

}  // namespace serosa::cutting::detail
