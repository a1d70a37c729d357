// Writes an Image as a PNG file (stb_image_write; no GL).
#pragma once

#include <filesystem>

#include "render/image.h"

namespace serosa::render {

/// Writes `image` to `path` as an opaque RGB PNG (alpha dropped: the picture shows the background
/// where nothing was drawn). Creates the parent directory if needed.
/// @throws std::runtime_error naming the path when the file cannot be written
void write_png(const Image& image, const std::filesystem::path& path);

}  // namespace serosa::render
