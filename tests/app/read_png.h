// A PNG the app wrote, read back as an RGBA image for the tests that judge pictures.
#pragma once

#include <stb/stb_image.h>  // the implementation is compiled in test_render_wound.cpp

#include <cstddef>
#include <filesystem>

#include "render/image.h"

namespace serosa::app::testing {

/// The picture at `png` (an empty image, width 0, when it cannot be read).
inline render::Image read_png(const std::filesystem::path& png) {
  int w = 0, h = 0, n = 0;
  stbi_uc* data = stbi_load(png.c_str(), &w, &h, &n, 4);
  render::Image img;
  if (data == nullptr) return img;
  img.width = w;
  img.height = h;
  img.rgba.assign(data, data + static_cast<std::size_t>(w) * static_cast<std::size_t>(h) * 4);
  stbi_image_free(data);
  return img;
}

}  // namespace serosa::app::testing
