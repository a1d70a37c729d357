// The cut's first step (docs/cutting.md, points 1 and 5): the candidate tets, the sign of every
// node against the blade's plane, each tet's case, the cut points of crossing edges, and whether
// a straddling tet is cut completely or only partly (partial tets are analysed at once,
// cutting/cut_partial.h).
#pragma once

#include "cutting/cut_state.h"

namespace serosa::cutting::detail {

/// Candidate tets: boxes meeting the blade's box, then grown by twice the tolerance so that
/// every tet around a node or cut point within tolerance of the polygon is found. Sets the
/// tolerance. False when there is none.
bool find_candidates(CutState& cs);

/// Signs of nodes (once per node), cases of tets, cut points of crossing edges; complete or
/// partial; the partial tets' analysis.
void classify(CutState& cs);

}  // namespace serosa::cutting::detail
