// The convex polygon a blade edge sweeps between two solver steps (docs/ARCHITECTURE.md
// "Cutting, in the paper's terms").
#pragma once

#include <cstdint>
#include <optional>

#include "cutting/convex_polygon.h"
#include "engine/math.h"

namespace serosa::cutting {

/// One pose of a blade's cutting edge, world coordinates (m): from the jaw hinge to the tip.
struct BladeEdge {
  Vec3 hinge = Vec3::Zero();
  Vec3 tip = Vec3::Zero();
};

/// Counted (never thrown) reasons a sweep produced no polygon, and repairs made to one.
struct SweepWarnings {
  std::int64_t non_finite = 0;   ///< a coordinate was NaN or infinite: skipped
  std::int64_t zero_length = 0;  ///< a pose's edge shorter than min_length_m: skipped
  std::int64_t zero_area = 0;    ///< the swept area vanished (no motion, motion along the edge)
  std::int64_t non_planar = 0;   ///< the quad was twisted; projected onto its best-fit plane
  [[nodiscard]] std::int64_t skipped() const { return non_finite + zero_length + zero_area; }
};

struct SweepOptions {
  double min_length_m = 1e-9;   ///< shorter blade edges are degenerate
  double merge_rel = 1e-9;      ///< ends closer than this times the edge length coincide
  double min_area_rel = 1e-12;  ///< swept area below this times diameter^2 is degenerate
  double planar_rel = 1e-6;     ///< twist above this times the diameter is counted non_planar
};

/// The polygon swept from `before` to `after`: the quad (before.hinge, before.tip, after.tip,
/// after.hinge), or the triangle (hinge, before.tip, after.tip) when the hinge did not move.
/// A twisted quad (the two edges not coplanar) is projected onto its best-fit plane (Newell
/// normal through the centroid) and counted in warnings.non_planar; a crossed quad becomes the
/// convex hull of its projected corners. Degenerate sweeps return std::nullopt and increment the
/// matching counter in `warnings`.
[[nodiscard]] std::optional<ConvexPolygon> sweep_polygon(const BladeEdge& before,
                                                         const BladeEdge& after,
                                                         SweepWarnings& warnings,
                                                         const SweepOptions& options = {});

}  // namespace serosa::cutting
