// Picture statistics (see image_stats.h).
#include "render/image_stats.h"

#include <algorithm>
#include <cmath>
#include <vector>

namespace serosa::render {

DominantColor most_common_color(const Image& image) {
  // Sorting the packed colours groups equal ones: no hash table, same answer every time.
  std::vector<std::uint32_t> packed;
  packed.reserve(image.rgba.size() / 4);
  for (std::size_t i = 0; i + 3 < image.rgba.size(); i += 4) {
    packed.push_back(static_cast<std::uint32_t>(image.rgba[i]) << 16 |
                     static_cast<std::uint32_t>(image.rgba[i + 1]) << 8 | image.rgba[i + 2]);
  }
  DominantColor out;
  if (packed.empty()) return out;
  std::sort(packed.begin(), packed.end());
  std::size_t best = 0, best_count = 0;
  for (std::size_t i = 0; i < packed.size();) {
    std::size_t j = i;
    while (j < packed.size() && packed[j] == packed[i]) ++j;
    if (j - i > best_count) {
      best = i;
      best_count = j - i;
    }
    i = j;
  }
  const std::uint32_t c = packed[best];
  out.rgb = {static_cast<std::uint8_t>(c >> 16), static_cast<std::uint8_t>(c >> 8),
             static_cast<std::uint8_t>(c)};
  out.fraction = static_cast<double>(best_count) / static_cast<double>(packed.size());
  return out;
}

namespace {

// Rec. 601 luma of every pixel, (height x width).
std::vector<double> luma(const Image& image) {
  std::vector<double> y(static_cast<std::size_t>(image.width) *
                        static_cast<std::size_t>(image.height));
  for (std::size_t i = 0; i < y.size(); ++i)
    y[i] =
        0.299 * image.rgba[4 * i] + 0.587 * image.rgba[4 * i + 1] + 0.114 * image.rgba[4 * i + 2];
  return y;
}

// The luma minus its 5 x 5 box mean (clamped at the borders), (height x width).
std::vector<double> high_pass(const std::vector<double>& y, int w, int h) {
  std::vector<double> out(y.size());
  for (int r = 0; r < h; ++r)
    for (int c = 0; c < w; ++c) {
      double sum = 0.0;
      for (int dr = -2; dr <= 2; ++dr)
        for (int dc = -2; dc <= 2; ++dc) {
          const int rr = std::clamp(r + dr, 0, h - 1), cc = std::clamp(c + dc, 0, w - 1);
          sum += y[static_cast<std::size_t>(rr) * static_cast<std::size_t>(w) +
                   static_cast<std::size_t>(cc)];
        }
      const std::size_t i =
          static_cast<std::size_t>(r) * static_cast<std::size_t>(w) + static_cast<std::size_t>(c);
      out[i] = y[i] - sum / 25.0;
    }
  return out;
}

}  // namespace

double flat_block_fraction(const Image& image, int block, double spread) {
  const int w = image.width, h = image.height;
  if (block < 1 || w < block || h < block) return 0.0;
  const std::vector<double> d = high_pass(luma(image), w, h);
  std::size_t flat = 0, blocks = 0;
  for (int r0 = 0; r0 + block <= h; r0 += block)
    for (int c0 = 0; c0 + block <= w; c0 += block) {
      double s = 0.0, s2 = 0.0;
      for (int r = r0; r < r0 + block; ++r)
        for (int c = c0; c < c0 + block; ++c) {
          const double v = d[static_cast<std::size_t>(r) * static_cast<std::size_t>(w) +
                             static_cast<std::size_t>(c)];
          s += v;
          s2 += v * v;
        }
      const double n = static_cast<double>(block) * block;
      const double var = std::max(s2 / n - (s / n) * (s / n), 0.0);
      ++blocks;
      if (std::sqrt(var) < spread) ++flat;
    }
  return static_cast<double>(flat) / static_cast<double>(blocks);
}

double blood_fraction(const Image& image) {
  const std::size_t n = image.rgba.size() / 4;
  if (n == 0) return 0.0;
  std::size_t blood = 0;
  for (std::size_t i = 0; i < n; ++i) {
    const int r = image.rgba[4 * i], g = image.rgba[4 * i + 1], b = image.rgba[4 * i + 2];
    if (r >= 40 && r <= 190 && 4 * g < r && 4 * b < r) ++blood;
  }
  return static_cast<double>(blood) / static_cast<double>(n);
}

}  // namespace serosa::render
