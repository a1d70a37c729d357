// The optional second pass (CutOptions::reopen_pinned; docs/cutting.md, point 7): tets the first
// pass coned from S's centre are cut again by the same blade, and the two deltas composed into
// one against the input mesh.
#pragma once

#include "cutting/convex_polygon.h"
#include "cutting/cut_types.h"

namespace serosa::cutting::detail {

/// The first pass's result is rebuilt locally (the tets whose boxes meet the grown blade box,
/// after the first delta), cut again by the same blade with the same tolerance, and the two
/// deltas are composed into `first`. Returns false (and leaves `first` as it was) when the
/// composition is not possible: a new node whose parents, flattened to nodes of `mesh`, are more
/// than four, or a node of the first pass no tet uses.
bool second_pass(const TetMesh& mesh, const ConvexPolygon& blade, const CutOptions& options,
                 const TetBoxQuery& query, CutResult& first);

}  // namespace serosa::cutting::detail
