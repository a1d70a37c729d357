// Headless pictures (see snapshot.h).
#include "render/snapshot.h"

#include <stdexcept>

#include "render/frame_renderer.h"
#include "render/png_writer.h"

namespace serosa::render {

Image render_image(OffscreenContext& context, const RenderFrame& frame,
                   const SnapshotOptions& options) {
  if (options.width <= 0 || options.height <= 0) {
    throw std::invalid_argument("render_image: image size must be positive");
  }
  context.make_current();
  context.resize(options.width, options.height);
  context.bind_framebuffer();
  {
    FrameRenderer renderer;  // its GL objects go before read-back returns
    renderer.draw(frame, options, options.width, options.height);
  }
  return context.read_image();
}

void render_to_png(OffscreenContext& context, const RenderFrame& frame,
                   const SnapshotOptions& options, const std::filesystem::path& png) {
  write_png(render_image(context, frame, options), png);
}

}  // namespace serosa::render
