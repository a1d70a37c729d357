// How much of what a blade polygon swept a cut opened: the area the polygon sweeps inside the
// tets it crossed, and the area of the crack the cut left (one side), both in current positions.
// Their ratio is 1 for a cut that opened everything the blade passed through; pinned or short
// partial tets (cutting/cut_partial.h) lower it.
#pragma once

#include <cstdint>
#include <span>

#include "cutting/convex_polygon.h"
#include "engine/tet_mesh.h"
#include "engine/topology_delta.h"

namespace serosa::cutting {

/// Area (m^2) of polygon ∩ tet over the given tets of `mesh` (current positions).
[[nodiscard]] double swept_area(const TetMesh& mesh, std::span<const std::int32_t> tets,
                                const ConvexPolygon& polygon);

/// Area (m^2) of one side of the crack `delta` opened in `after` (= apply(before, delta)): the
/// faces of its added tets that lie on the polygon (within tol_m, m) and are boundary faces of
/// `after`, halved. O(tets of after).
[[nodiscard]] double crack_area(const TetMesh& after, const TopologyDelta& delta,
                                const ConvexPolygon& polygon, double tol_m);

/// Smallest mean-ratio quality (rest positions) of the tets `delta` added to `after`; 1 for none.
[[nodiscard]] double min_added_quality(const TetMesh& after, const TopologyDelta& delta);

}  // namespace serosa::cutting
