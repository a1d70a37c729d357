// CutMethod: the three ways to cut a mesh by a blade polygon, behind one call, for the
// accuracy-versus-time comparison, `serosa cut --method` and the benchmarks.
//   pattern: the paper's pattern-based subdivision (cutting/cut_mesh.h): exact path, volume kept
//   remove:  element removal (cutting/remove_cut.h): drop every tet the blade touches
//   snap:    node snapping (cutting/snap_cut.h): move nearby nodes onto the plane, separate
#pragma once

#include <optional>
#include <string_view>

#include "cutting/convex_polygon.h"
#include "cutting/cut_mesh.h"
#include "engine/tet_mesh.h"

namespace serosa::cutting {

enum class CutMethod { kPattern, kRemove, kSnap };

/// "pattern", "remove" or "snap".
[[nodiscard]] std::string_view to_string(CutMethod method);

/// The method named `name` ("pattern", "remove", "snap"); std::nullopt for anything else.
[[nodiscard]] std::optional<CutMethod> parse_cut_method(std::string_view name);

/// Cuts `mesh` by `blade` with `method`; apply(mesh, result.delta) performs it. options:
/// classify_rel for all three (snap uses SnapOptions' default quality floor). `query` finds
/// candidate tets (a BVH's as_query(); brute force when empty).
[[nodiscard]] CutResult cut_with(CutMethod method, const TetMesh& mesh, const ConvexPolygon& blade,
                                 const CutOptions& options = {}, const TetBoxQuery& query = {});

}  // namespace serosa::cutting
