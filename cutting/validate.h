// The cut invariant checker: used by the tests after every cut, and by debug
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
  /// beyond geometry_tol_m on each side with a crossing edge meeting the polygon), every
  /// connected piece lies on one side of the plane (within geometry_tol_m), and the rest volume
  /// of the pieces on the positive side equals the exact clipped volume of `before` (to
  /// volume_rel), the plane clipping each tet of `before` affinely (cut points found in current
  /// positions, volumes in rest positions).
  bool expect_separated = false;
  /// Nodes within this distance (m) of the plane count as on it in the exact clipped volume:
  /// the cut's own classification tolerance (CutStats::tolerance_m).
  double plane_tol_m = 0.0;
  /// Nodes left in no tet are allowed: a stroke cut by ProgressiveCut releases the nodes of its
  /// previous pieces at every step, so `after` is checked against the mesh before the stroke.
  bool unused_nodes_ok = false;
};

struct CutCheckReport {
  bool ok = false;
  std::vector<std::string> problems;  ///< one sentence each
  double volume_before_m3 = 0.0;
  double volume_after_m3 = 0.0;
  std::int64_t boundary_faces_kept = 0;      ///< boundary faces present before, unchanged
  std::int64_t boundary_faces_on_old = 0;    ///< new faces lying on the old surface
  std::int64_t boundary_faces_on_blade = 0;  ///< new faces lying on the blade polygon
  double blade_face_area_m2 = 0.0;  ///< their total area (current positions): both crack sides
  double min_quality = 0.0;         ///< smallest mean-ratio quality after the cut
  std::int32_t components = 0;      ///< connected pieces after (expect_separated only)
  double positive_volume_m3 = 0.0;  ///< rest volume of the positive pieces (idem)
  double clipped_volume_m3 = 0.0;   ///< exact positive clipped volume of before (idem)
};

/// Checks `after` = `before` cut by `blade` (geometry in current positions x; volumes in rest):
/// engine's check_mesh (finite, positive volumes, faces shared by at most two tets, consistent
/// orientation); no new unreferenced node (unless unused_nodes_ok); total and per-group
/// volume conserved; every boundary face of `after` was a boundary face of
/// `before`, lies on its surface, or lies on the blade polygon; with expect_separated, no tet
/// crosses the polygon.
[[nodiscard]] CutCheckReport check_cut(const TetMesh& before, const TetMesh& after,
                                       const ConvexPolygon& blade,
                                       const CutCheckOptions& options = {});

/// Number of connected components of the mesh, tets connected through shared nodes.
[[nodiscard]] std::int32_t count_components(const TetMesh& mesh);
/// Same, over the tets of one group only (how many pieces an organ part is in).
[[nodiscard]] std::int32_t count_components(const TetMesh& mesh, std::uint16_t group);

/// Component id (0-based, dense) of every tet, tets connected through shared nodes.
[[nodiscard]] std::vector<std::int32_t> tet_components(const TetMesh& mesh);

/// Exact rest volume (m^3) of the part of `mesh` on the positive side of the plane
/// {p : normal . p = offset}: each tet is clipped by the plane of its nodes' signed distances
/// (current positions x; |distance| <= plane_tol_m counts as 0), the cut points carried to rest
/// positions by the same edge parameters.
[[nodiscard]] double clipped_positive_volume(const TetMesh& mesh, const Vec3& normal, double offset,
                                             double plane_tol_m = 0.0);

}  // namespace serosa::cutting
