// Picture statistics (see image_stats.h).
#include "render/image_stats.h"

#include <algorithm>
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

}  // namespace serosa::render
