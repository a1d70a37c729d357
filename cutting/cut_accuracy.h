// What one cut did to a mesh's geometry, for the accuracy-versus-time comparison of the cutting
// methods (bench/cutting BM_Method, `serosa bench` cutting part): volume lost, minimum quality,
// and where the cut surface lies relative to the blade polygon.
#pragma once

#include "cutting/convex_polygon.h"
#include "engine/tet_mesh.h"

namespace serosa::cutting {

struct CutAccuracy {
  double volume_before_m3 = 0.0;  ///< rest volume of all tets before, m³
  double volume_lost_m3 = 0.0;    ///< rest volume before minus after, m³ (element removal > 0)
  double volume_lost_rel = 0.0;   ///< volume_lost_m3 / volume_before_m3
  double min_quality = 0.0;  ///< smallest mean-ratio quality after (rest, engine/mesh_quality.h)
  /// The cut surface: boundary faces after the cut that were not boundary faces before and do not
  /// lie on the old boundary (both sides of the crack, or the walls of a removed channel).
  double max_dist_m = 0.0;        ///< largest distance of their vertices from the blade polygon, m
  double mean_dist_m = 0.0;       ///< area-weighted mean of that distance over them, m
  double max_plane_dist_m = 0.0;  ///< largest distance of their vertices from the blade's plane, m
  double cut_area_m2 = 0.0;       ///< their total area (both sides), m²
  std::int64_t cut_faces = 0;     ///< how many
};

/// Distance (m) from p to the convex polygon `blade` (to its plane where p projects inside it,
/// else to its outline).
[[nodiscard]] double polygon_distance(const ConvexPolygon& blade, const Vec3& p);

/// Measures the cut that turned `before` into `after` (apply(before, delta)) along `blade`, at
/// rest positions. `h` (m, > 0) is the mesh's edge length scale: old boundary faces within 3 h of
/// the blade's box are the ones a new face may lie on (coplanar within 1e-9 h). O(tets + faces ×
/// nearby old faces).
[[nodiscard]] CutAccuracy measure_cut(const TetMesh& before, const TetMesh& after,
                                      const ConvexPolygon& blade, double h);

}  // namespace serosa::cutting
