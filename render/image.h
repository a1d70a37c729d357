// Image: an 8-bit RGBA picture in memory (no GL).
#pragma once

#include <array>
#include <cstdint>
#include <vector>

namespace serosa::render {

/// An RGBA8 image, rows top to bottom (the first row is the top of the picture, as in PNG).
/// Alpha is the coverage: 0 where nothing was drawn, 255 where a surface or line covers the
/// pixel fully, in between on anti-aliased edges.
struct Image {
  int width = 0;
  int height = 0;
  std::vector<std::uint8_t> rgba;  ///< (height x width x 4)

  [[nodiscard]] std::array<std::uint8_t, 4> at(int x, int y) const {
    const std::size_t i = 4 * (static_cast<std::size_t>(y) * static_cast<std::size_t>(width) +
                               static_cast<std::size_t>(x));
    return {rgba[i], rgba[i + 1], rgba[i + 2], rgba[i + 3]};
  }
};

}  // namespace serosa::render
