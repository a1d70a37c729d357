// StrokeSurface: the surface a bent stroke swept, as a height field over the plane that fits its
// samples. A roll of the wrist or a drift across the blade plane while the jaws close sweeps a
// surface that no plane holds; cut in its best-fit plane, the crack lies up to the stroke's
// deviation from where the blades passed. The height field h(u, v) is the piecewise-linear
// terrain over the Delaunay triangulation of the samples' projections, held at its boundary's
// value beyond it. Flattening, x -> x - h(u(x), v(x)) n, is a shear along the normal: it keeps
// volume (its Jacobian's determinant is 1) and moves the swept surface onto the plane. The
// pattern cut classifies the flattened positions against the plane; its new nodes are cut points
// on edges, weighted combinations of their parents, so in the real positions each crossed tet is
// cut by the affine image of a plane: the crack is welded (neighbours share the cut points of
// their shared edges), every piece keeps a positive volume wherever flattening leaves the
// tet's orientation, and the crack follows the swept surface to within the terrain's departure
// from linear across one tet (cutting/flat_cut.h does the cut).
#pragma once

#include <array>
#include <optional>
#include <span>
#include <vector>

#include "cutting/planar_hull.h"
#include "engine/math.h"

namespace serosa::cutting {

class StrokeSurface {
 public:
  /// The terrain over `fit` through `points` (m, world; their heights are their distances from
  /// the plane). Points whose projections lie within `merge_m` (m) of an earlier one are merged
  /// into it. std::nullopt when fewer than three distinct projections remain, a coordinate is not
  /// finite.
  [[nodiscard]] static std::optional<StrokeSurface> make(const PlaneFit& fit,
                                                         std::span<const Vec3> points,
                                                         double merge_m);

  /// Height (m) above the plane at plane coordinates q (m): linear in the triangle holding q,
  /// the nearest boundary point's height outside the triangulated region.
  [[nodiscard]] double height(const Vec2& q) const;
  /// x moved along the plane's normal by minus its height: the swept surface onto the plane.
  [[nodiscard]] Vec3 flatten(const Vec3& x) const {
    return x - height(m_fit.to_plane(x)) * m_fit.normal;
  }

  [[nodiscard]] const PlaneFit& fit() const noexcept { return m_fit; }
  /// Largest |height| (m): flattening moves no point farther.
  [[nodiscard]] double max_abs_height() const noexcept { return m_max_abs_h; }
  /// Steepest triangle's |grad h| (dimensionless).
  [[nodiscard]] double max_slope() const noexcept { return m_max_slope; }
  [[nodiscard]] std::size_t num_vertices() const noexcept { return m_q.size(); }
  [[nodiscard]] std::size_t num_triangles() const noexcept { return m_tris.size(); }

 private:
  StrokeSurface() = default;
  void build_bins();
  [[nodiscard]] double boundary_height(const Vec2& q) const;

  PlaneFit m_fit;
  std::vector<Vec2> m_q;                    ///< (k) vertices in plane coordinates, m
  std::vector<double> m_h;                  ///< (k) their heights, m
  std::vector<std::array<int, 3>> m_tris;   ///< (t) counter-clockwise triangles of vertex indices
  std::vector<std::array<int, 2>> m_edges;  ///< (b) boundary edges of the triangulation
  double m_max_abs_h = 0.0;
  double m_max_slope = 0.0;
  // Point location: a grid of m_nx x m_ny cells over the vertices' box, each listing the
  // triangles whose boxes meet it (compressed rows).
  Vec2 m_lo = Vec2::Zero();
  double m_cell = 1.0;  ///< m
  int m_nx = 1, m_ny = 1;
  std::vector<int> m_bin_start;  ///< (m_nx m_ny + 1)
  std::vector<int> m_bin_tris;
};

/// Delaunay triangulation (Bowyer-Watson) of distinct points, counter-clockwise triangles of
/// indices into `points`; the triangles of a nearly collinear hull may be missing.
[[nodiscard]] std::vector<std::array<int, 3>> delaunay2d(const std::vector<Vec2>& points);

}  // namespace serosa::cutting
