// The organs' static surroundings (no GL): an abdomen built around a support plane, so that the
// endoscope sees a posterior wall with bowel and fat around the organs instead of a black void.
// Plain geometry, generated once per scene; drawn by FrameRenderer from RenderFrame::scenery.
#pragma once

#include <array>
#include <cstdint>

#include "render/render_frame.h"

namespace serosa::render {

/// Where the abdomen goes: the plane the organs rest on and the organs' extent (world, m).
struct AbdomenPlacement {
  std::array<float, 3> point_m{0.0f, 0.0f, 0.0f};      ///< a point of the support plane, m
  std::array<float, 3> normal{0.0f, 0.0f, 1.0f};       ///< the plane's normal, towards the organs
  std::array<float, 3> organs_lo_m{0.0f, 0.0f, 0.0f};  ///< the organs' bounding box, min, m
  std::array<float, 3> organs_hi_m{0.0f, 0.0f, 0.0f};  ///< the organs' bounding box, max, m
  /// Orients the layout in the plane (the patient's cranial direction, say; need not be unit or
  /// in the plane). Parallel to the normal or zero: an axis of the world is used instead.
  std::array<float, 3> up_hint{0.0f, 1.0f, 0.0f};
};

/// Sizes and counts of the abdomen. "Footprint": the organs' bounding box projected onto the
/// plane, as a rectangle in the plane's frame (its axes: up_hint in the plane, and normal x that).
struct AbdomenDimensions {
  /// The wall: a square sheet reaching this far from the footprint's centre along both in-plane
  /// axes, m. It lies on the plane within wall_flat_radius_m of that centre (~0.3 m: the
  /// posterior wall) and rises beyond it, by wall_rim_curvature_per_m times the square of the
  /// distance beyond (the cavity's flanks: an oblique view finds wall, not a void, at its far
  /// edge; 4.5 cm up at the middle of each side, 23 cm at the corners).
  double wall_half_width_m = 0.45;
  double wall_flat_radius_m = 0.30;
  double wall_rim_curvature_per_m = 2.0;
  /// Grid cells along each side of the wall: (cells + 1)^2 vertices, 2 cells^2 triangles; the
  /// cells grow from ~2.5 mm under the organs to ~2.5 cm at the rim.
  int wall_cells = 110;
  /// The largest height of the wall's undulation above or below the plane, m.
  double wall_amplitude_m = 0.003;
  /// Within the footprint grown by this margin the wall only dips below the plane (the organs
  /// lie on the plane there), m; it rises again over the next 3 cm.
  double wall_clearance_m = 0.01;
  /// The least in-plane gap between the bowel (and fat) and the footprint, m.
  double bowel_clearance_m = 0.015;
  double bowel_radius_min_m = 0.010;  ///< the thinnest bowel loop's radius, m
  double bowel_radius_max_m = 0.016;  ///< the thickest bowel loop's radius, m
  /// Rings of bowel loops around the footprint, each ring broken into loops (tubes with rounded
  /// ends) about loop_length_m long; the gaps between them take fat lobules every other gap.
  int bowel_rings = 4;
  double loop_length_m = 0.12;
  int tube_sides = 16;            ///< vertices around a tube's cross-section
  double tube_section_m = 0.006;  ///< spacing of a tube's cross-sections along it, m
  double wiggle_m = 0.012;        ///< how far a loop meanders outwards off its ring, m
};

/// The abdomen around the organs, in world coordinates (m):
/// - the posterior wall (SceneryMaterial::kPeritoneum): the wall sheet on the support plane,
///   undulating by up to wall_amplitude_m, never above the plane within the footprint plus
///   wall_clearance_m, its rim rising beyond wall_flat_radius_m; smooth normals, pointing to the
///   organs' side;
/// - small bowel (kBowel): bowel_rings rings of tubes of radius bowel_radius_min_m to
///   bowel_radius_max_m lying on the plane (their centre line one radius above it), meandering
///   along curves at a constant distance from the footprint, never nearer than bowel_clearance_m
///   to it (so they never meet the organs' box), the rings staggered so that a camera over the
///   organs sees bowel all around them;
/// - mesenteric fat (kFat): flattened ellipsoid lobules in every other gap between loops, as far
///   from the footprint as the bowel.
/// Deterministic: the same placement and dimensions give the same mesh, bit for bit. The
/// version is content_version() of the result.
[[nodiscard]] Scenery make_abdomen(const AbdomenPlacement& placement,
                                   const AbdomenDimensions& dims = {});

/// A hash of the scenery's arrays (FNV-1a over their bytes), never 0 for a non-empty scenery and
/// 0 for an empty one: a version that changes when, and in practice only when, the contents do.
[[nodiscard]] std::uint64_t content_version(const Scenery& scenery);

}  // namespace serosa::render
