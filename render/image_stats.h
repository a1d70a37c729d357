// Statistics of a picture (no GL): how much of it one colour takes, so that tests and tools can
// tell a scene from a mostly empty background.
#pragma once

#include <array>
#include <cstdint>

#include "render/image.h"

namespace serosa::render {

/// The most common exact RGB colour of a picture (alpha ignored) and the fraction of its pixels
/// that have it, in [0, 1]; {0, 0, 0} and 0 for an empty picture. Ties go to the smallest colour
/// (packed as 0xRRGGBB), so the answer is deterministic.
struct DominantColor {
  std::array<std::uint8_t, 3> rgb{0, 0, 0};
  double fraction = 0.0;
};
[[nodiscard]] DominantColor most_common_color(const Image& image);

/// How much of a picture carries no detail: the fraction of its whole block x block tiles in which
/// the grey level (Rec. 601 luma, 0..255) minus its 5 x 5 box mean varies by less than
/// `spread` grey levels (standard deviation). A smooth, uniformly shaded surface is flat; tissue
/// with vessels, lobules and wet glints is not. 0 for a picture smaller than one tile.
[[nodiscard]] double flat_block_fraction(const Image& image, int block = 16, double spread = 1.0);

/// The fraction of a picture's pixels that read as blood: a dark, saturated red (red from 40 to
/// 190 of 255, green and blue under a quarter of it). Tissue, fat and the instruments do not.
[[nodiscard]] double blood_fraction(const Image& image);

}  // namespace serosa::render
