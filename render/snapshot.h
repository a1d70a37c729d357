// Headless pictures: draw a RenderFrame offscreen and read it back or write it as a PNG.
#pragma once

#include <filesystem>

#include "render/gl_context.h"
#include "render/image.h"
#include "render/render_frame.h"
#include "render/snapshot_options.h"

namespace serosa::render {

/// Draws `frame` into `context` (resized to options.width x options.height) with a fresh
/// FrameRenderer and reads the picture back (rows top to bottom, alpha = coverage).
/// @throws std::invalid_argument for an invalid frame, std::runtime_error for GL failures
[[nodiscard]] Image render_image(OffscreenContext& context, const RenderFrame& frame,
                                 const SnapshotOptions& options);

/// render_image, then write_png to `png` (parent directories are created).
void render_to_png(OffscreenContext& context, const RenderFrame& frame,
                   const SnapshotOptions& options, const std::filesystem::path& png);

}  // namespace serosa::render
