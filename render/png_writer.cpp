// PNG output through stb_image_write; the only translation unit that holds its implementation.
#include "render/png_writer.h"

#include <stdexcept>
#include <vector>

#define STB_IMAGE_WRITE_IMPLEMENTATION
#if defined(__GNUC__)
#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wold-style-cast"
#pragma GCC diagnostic ignored "-Wdouble-promotion"
#pragma GCC diagnostic ignored "-Wmissing-field-initializers"
#pragma GCC diagnostic ignored "-Wsign-compare"
#pragma GCC diagnostic ignored "-Wunused-parameter"
#endif
#include <stb/stb_image_write.h>
#if defined(__GNUC__)
#pragma GCC diagnostic pop
#endif

namespace serosa::render {

void write_png(const Image& image, const std::filesystem::path& path) {
  const auto w = static_cast<std::size_t>(image.width);
  const auto h = static_cast<std::size_t>(image.height);
  if (image.width <= 0 || image.height <= 0 || image.rgba.size() != w * h * 4) {
    throw std::runtime_error("write_png: image size does not match its pixels (" + path.string() +
                             ")");
  }
  std::vector<std::uint8_t> rgb(w * h * 3);
  for (std::size_t i = 0; i < w * h; ++i) {
    for (std::size_t k = 0; k < 3; ++k) rgb[3 * i + k] = image.rgba[4 * i + k];
  }
  if (path.has_parent_path()) {
    std::error_code ec;
    std::filesystem::create_directories(path.parent_path(), ec);
  }
  const std::string name = path.string();
  if (stbi_write_png(name.c_str(), image.width, image.height, 3, rgb.data(), image.width * 3) ==
      0) {
    throw std::runtime_error("write_png: cannot write " + name);
  }
}

}  // namespace serosa::render
