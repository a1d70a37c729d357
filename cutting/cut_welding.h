// Which parts of the cut open (docs/cutting.md, points 4 and 5): a cut edge opens (two nodes,
// one per side) or stays welded (one node); a coplanar node is cloned (the clone goes to the
// positive side) or stays welded. Both are decided once per edge or node, so every tet around it
// agrees. After classify and decide_faces, before the pieces are emitted.
#pragma once

#include "cutting/cut_state.h"

namespace serosa::cutting::detail {

/// An edge opens iff its cut point is strictly inside and no pinned tet holds it.
void decide_edges(CutState& cs);

/// Clones of coplanar nodes, in ascending node order: a node inside the grown polygon is cloned
/// when every tet around it lets it open and both sides use it (docs/cutting.md, point 5).
void decide_clones(CutState& cs);

}  // namespace serosa::cutting::detail
