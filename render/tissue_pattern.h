// The tissue's pattern (no GL): a periodic 3D volume the visual view's shader samples at each
// surface point's rest (material) position, so that vessels, fat lobules and mottling stay on the
// tissue as it deforms and is cut, and a cut face shows the same pattern the tissue had inside.
// Made procedurally here (gradient noise and cell noise), no image asset.
#pragma once

#include <cstdint>
#include <vector>

namespace serosa::render {

/// Channels of one voxel, each in [0, 255].
enum TissueChannel : int {
  kVessels = 0,  ///< R: a vessel network, 255 on a vessel's centre line, 0 between vessels
  kLobules = 1,  ///< G: the borders between fat lobules, 255 on a border, 0 inside a lobule
  kMottle = 2,   ///< B: smooth colour variation (fractal noise), mean about 128
  kRelief = 3,   ///< A: fine relief of the surface (fractal noise), mean about 128
};

struct TissuePattern {
  int size = 0;                    ///< voxels along each axis: the volume is size^3
  std::vector<std::uint8_t> rgba;  ///< (size^3 x 4) channels as TissueChannel, x fastest
};

/// The pattern of size^3 voxels (size >= 4). Deterministic; it repeats with a period of `size`
/// voxels along each axis, so a repeating texture shows no seams.
[[nodiscard]] TissuePattern make_tissue_pattern(int size);

/// The renderer's pattern, kTissuePatternSize^3, made once per process and never changed.
[[nodiscard]] const TissuePattern& tissue_pattern();
inline constexpr int kTissuePatternSize = 64;

/// How far one repeat of the pattern reaches on the tissue, m: the vessel network's meshes are
/// about a fifth of it, fat lobules about a seventh.
inline constexpr float kTissuePatternPeriodM = 0.03f;

}  // namespace serosa::render
