// Cutting a bent stroke (cutting/stroke_surface.h) with the pattern cut: the mesh's current
// positions are flattened, for the cut alone, so that the stroke's swept surface lies on its
// plane; the cut classifies those positions against the stroke's polygon and returns a delta of
// weights, which apply() then carries to the real positions. Only the nodes of tets near the
// polygon are flattened, lazily, through the candidate query; the real positions are back in
// place when a call returns. The nodes a cut creates take their parents' flattened positions
// combined by the same weights, so the second polygon of a stroke that ended part way finds the
// first one's crack on its plane.
#pragma once

#include <cstdint>
#include <optional>
#include <span>
#include <vector>

#include "cutting/convex_polygon.h"
#include "cutting/cut_mesh.h"
#include "cutting/stroke_surface.h"
#include "engine/tet_mesh.h"
#include "engine/topology_delta.h"

namespace serosa::cutting {
class TetBvh;

/// A tet whose flattened volume is less than this fraction of its real volume (or of the other
/// sign) is turned too far by flattening: the stroke is cut in its plane instead.
inline constexpr double kMinFlattenedVolumeRatio = 0.05;

/// Flattened positions of a mesh's nodes, each computed once (m, world).
class FlattenedPositions {
 public:
  explicit FlattenedPositions(const StrokeSurface& surface) : m_surface(surface) {}

  /// Node n's flattened position (from mesh.x when first asked).
  [[nodiscard]] const Vec3& of(const TetMesh& mesh, std::int32_t n);
  /// The nodes apply(mesh, delta) appended take their parents' flattened positions, weighted.
  void added(const TetMesh& mesh, const TopologyDelta& delta);
  [[nodiscard]] const StrokeSurface& surface() const noexcept { return m_surface; }

 private:
  const StrokeSurface& m_surface;
  std::vector<Vec3> m_x;            ///< (n) flattened positions, m
  std::vector<std::uint8_t> m_has;  ///< (n) 1 where m_x holds one
};

/// Swaps flattened positions into mesh.x for nodes asked for, and the real ones back on
/// destruction (or restore()).
class FlattenedScope {
 public:
  FlattenedScope(TetMesh& mesh, FlattenedPositions& flat) : m_mesh(mesh), m_flat(flat) {}
  FlattenedScope(const FlattenedScope&) = delete;
  FlattenedScope& operator=(const FlattenedScope&) = delete;
  ~FlattenedScope() { restore(); }

  /// Flattens tet t's nodes in mesh.x (those not yet flattened).
  void flatten_tet(std::int32_t t);
  /// The real position of node n while flattened.
  [[nodiscard]] Vec3 real(std::int32_t n) const;
  void restore();

 private:
  TetMesh& m_mesh;
  FlattenedPositions& m_flat;
  std::vector<std::int32_t> m_nodes;  ///< nodes flattened, in order
  std::vector<Vec3> m_saved;          ///< their real positions, m
  std::vector<std::int32_t> m_slot;   ///< (n) 1 + its index in m_nodes; 0: not flattened
};

/// True when flattening keeps every tet near `polygons` (the stroke's, in its plane) turned the
/// way it was, each with at least kMinFlattenedVolumeRatio of its volume.
[[nodiscard]] bool flattening_keeps_tets(TetMesh& mesh, FlattenedPositions& flat,
                                         const std::vector<ConvexPolygon>& polygons,
                                         const TetBvh& bvh);

/// What a flattened cut measured before its real positions came back.
struct FlatCutResult {
  CutResult cut;
  double swept_area_m2 = 0.0;  ///< the polygon ∩ the tets it crossed, flattened, m²
};

/// The pattern cut of `mesh` by `polygon` in flattened positions (mesh.x is real again on
/// return). `bvh` holds the real positions' boxes.
[[nodiscard]] FlatCutResult cut_flattened(TetMesh& mesh, FlattenedPositions& flat,
                                          const ConvexPolygon& polygon, const CutOptions& options,
                                          const TetBvh& bvh);

/// Area of one side of the crack `delta` opened in `after` (crack_area in flattened positions).
[[nodiscard]] double flattened_crack_area(TetMesh& after, FlattenedPositions& flat,
                                          const TopologyDelta& delta, const ConvexPolygon& polygon,
                                          double tol_m);

/// How far a crack cut along `fit`'s plane lies from the swept surface's `points` (m) inside the
/// tissue: the largest height above the plane of a point inside a tet of `mesh`, with the tet's
/// nodes flattened by `flat` (its crack is then the tet's affine image of the plane), or at
/// their current positions when `flat` is null (the crack is the plane). 0 when no point is in
/// the tissue. m.
[[nodiscard]] double crack_deviation(const TetMesh& mesh, const TetBvh& bvh,
                                     std::span<const Vec3> points, const PlaneFit& fit,
                                     FlattenedPositions* flat);

/// A copy of `mesh` with every node flattened (for the cut checker).
[[nodiscard]] TetMesh flattened_copy(const TetMesh& mesh, FlattenedPositions& flat);

}  // namespace serosa::cutting
