// The cut invariant checker (issue 3, item 8): used by the tests after every cut, and by debug
// builds. Never throws on a bad mesh: it says what is wrong.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "cutting/convex_polygon.h"
#include "engine/tet_mesh.h"

namespace serosa::cutting {

struct CutCheckOptions {
  /// Relative tolerance of total and per-group rest volume conservation.
  double volume_rel = 1e-12;
  /// Distance (m) within which a boundary face lies on the blade's plane, inside its outline,
  /// or on the old surface.
  double geometry_tol_m = 1e-9;
  /// The blade covers the whole section: additionally no tet may cross the blade (a node
  /// beyond geometry_tol_m on each side with a crossing edge meeting the polygon).
  bool expect_separated = false;
};

struct CutCheckReport {
  bool ok = false;
  std::vector<std::string> problems;  ///< one sentence each
  double volume_before_m3 = 0.0;
  double volume_after_m3 = 0.0;
  std::int64_t boundary_faces_kept = 0;      ///< boundary faces present before, unchanged
  std::int64_t boundary_faces_on_old = 0;    ///< new faces lying on the old surface
  std::int64_t boundary_faces_on_blade = 0;  ///< new faces lying on the blade polygon
  double min_quality = 0.0;                  ///< smallest mean-ratio quality after the cut
};

/// Checks `after` = `before` cut by `blade` (geometry in current positions x; volumes in rest):
/// engine's check_mesh (finite, positive volumes, faces shared by at most two tets, consistent
/// orientation); no new unreferenced node; total and per-group volume conserved; every boundary
/// face of `after` was a boundary face of `before`, lies on its surface, or lies on the blade
/// polygon; with expect_separated, no tet crosses the polygon.
[[nodiscard]] CutCheckReport check_cut(const TetMesh& before, const TetMesh& after,
                                       const ConvexPolygon& blade,
                                       const CutCheckOptions& options = {});

/// Number of connected components of the mesh, tets connected through shared nodes.
[[nodiscard]] std::int32_t count_components(const TetMesh& mesh);

}  // namespace serosa::cutting
