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

}  // namespace serosa::render
