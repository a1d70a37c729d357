// ScissorsStroke: what a pair of scissors swept in one closing stroke, however they moved. Each
// step the jaws close, the stroke samples the blade edges between the step's two poses (hinge and
// both blade tips, at most kStrokeArcStep of jaw half-angle apart) and pins every sample to the
// tissue under it: the tet that holds it (or the nearest one, extrapolated) and its barycentric
// weights in that step's positions. When the stroke ends, the samples are carried to where that
// tissue is now, so a stroke through tissue the grasper pulls or the FEM deforms cuts the
// material the blades passed through, not the empty space they left behind. The stroke is cut
// as convex polygons in the plane that fits those samples best: one across both blades when the
// jaws closed, one per blade (up to where it stopped) when the stroke ended part way. When the
// samples bend away from that plane (a roll or a drift across it), the polygons come with the
// stroke's surface (cutting/stroke_surface.h), through the samples and points along each sampled
// blade edge, and the cut follows it (cutting/flat_cut.h).
#pragma once

#include <array>
#include <cstdint>
#include <optional>
#include <utility>
#include <vector>

#include "cutting/convex_polygon.h"
#include "cutting/planar_hull.h"
#include "cutting/stroke_surface.h"
#include "engine/state_blocks.h"
#include "engine/tet_mesh.h"
#include "engine/tool_state.h"

namespace serosa::cutting {
class TetBvh;

/// Jaw half-angle between two samples of a blade tip, rad.
inline constexpr double kStrokeArcStep = 0.05;
/// A sample is pinned to a tet found within this distance (m), doubled up to 16 times as far.
/// Farther than that from every tet, it stays where it was in the world.
inline constexpr double kStrokeTrackRadius = 3e-3;
/// Samples farther than this (m) from their best-fit plane make a bent stroke: it is cut along
/// its swept surface. Nearer, the plane is within a few classification tolerances of every
/// sample and is cut as it is.
inline constexpr double kBentStrokeTol = 5e-5;
/// Points sampled along each blade edge between the hinge and the tip for the stroke's surface.
inline constexpr int kBladeEdgePoints = 3;

/// The polygons a stroke is cut with, and how far its samples lie from their plane.
struct StrokePolygons {
  std::vector<ConvexPolygon> polygons;
  std::vector<std::int32_t> blades;  ///< blade of each polygon (0 for the one across both)
  /// The polygons' plane; its deviation_m is the largest distance of a (carried) sample from it.
  PlaneFit fit;
  /// The swept surface over that plane, for a bent stroke (fit.deviation_m > kBentStrokeTol);
  /// else std::nullopt. The cutting stage still cuts in the plane where the surface folds over
  /// it (cutting/cutting_stage.h).
  std::optional<StrokeSurface> surface;
  /// (p) points of the swept surface where the tissue is now: the carried samples and
  /// kBladeEdgePoints along each sampled blade edge, m.
  std::vector<Vec3> surface_points_m;
};

class ScissorsStroke {
 public:
  /// A stroke that begins at `start` on a mesh of topology version `topology_version`.
  ScissorsStroke(const ToolState& start, std::uint64_t topology_version);
  /// Goes on with a stroke in progress (a cutting block's: engine/state_blocks.h); `scratch`: a
  /// buffer for its tree queries, kept by the caller from one step to the next (no allocation).
  explicit ScissorsStroke(StrokeRecord record, std::vector<std::int32_t> scratch = {})
      : m_rec(std::move(record)), m_candidates(std::move(scratch)) {}

  /// Samples the blades closing from `before` to `now` (same stroke), pinned to `mesh` (current
  /// positions; `bvh` refitted to them).
  void sweep(const ToolState& before, const ToolState& now, const TetMesh& mesh, const TetBvh& bvh);

  /// A hook's stroke (the same pinning and cut, cutting/cutting_stage.h): samples the live
  /// segment [a, b] (both ends and its middle), pinned to `mesh` as sweep() pins its samples.
  void add_segment(const Vec3& a, const Vec3& b, const TetMesh& mesh, const TetBvh& bvh);
  /// Counts one step of a hook's stroke (sweep() counts its own).
  void count_step() noexcept { ++m_rec.steps; }

  /// The samples carried to `mesh`'s current positions (world positions where the mesh changed
  /// topology since the stroke began, or a sample is pinned to no tet).
  void carried(const TetMesh& mesh, std::vector<Vec3>& out) const;
  /// What to cut when the stroke ends with the jaws at `end` (closed when end.jaw_rad <=
  /// closed_rad).
  [[nodiscard]] StrokePolygons polygons(const TetMesh& mesh, const ToolState& end,
                                        double closed_rad) const;

  [[nodiscard]] const ToolState& start() const noexcept { return m_rec.start; }
  [[nodiscard]] const std::vector<StrokeSample>& samples() const noexcept { return m_rec.samples; }
  [[nodiscard]] std::size_t size() const noexcept { return m_rec.samples.size(); }
  [[nodiscard]] std::uint64_t steps() const noexcept { return m_rec.steps; }
  /// What it swept so far, for the state; the stroke is left empty.
  [[nodiscard]] StrokeRecord release() noexcept { return std::move(m_rec); }
  /// The query buffer back, for the next step's stroke.
  [[nodiscard]] std::vector<std::int32_t> release_scratch() noexcept {
    return std::move(m_candidates);
  }

 private:
  void add(const Vec3& x, std::int32_t blade, const TetMesh& mesh, const TetBvh& bvh);

  StrokeRecord m_rec;
  std::vector<std::int32_t> m_candidates;  // scratch
};

/// The pose a fraction s in [0, 1] of the way from a to b (tip and jaw linear, turn slerped).
[[nodiscard]] ToolState interpolate(const ToolState& a, const ToolState& b, double s);

}  // namespace serosa::cutting
