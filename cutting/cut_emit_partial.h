// The pieces of a partial (or pinned) tet (docs/cutting.md, point 5): every face triangulated
// so that both tets sharing it agree, and the tet coned from one welded apex on the plane.
#pragma once

#include "cutting/cut_state.h"

namespace serosa::cutting::detail {

/// Emits partial tet t's pieces in group g: coned from its apex (a pinned tet: from S's centre
/// when it has one, else from its centroid) over its four faces' triangulations.
void emit_partial(CutState& cs, const Tet& t, const TetInfo& info, std::uint16_t g);

}  // namespace serosa::cutting::detail
