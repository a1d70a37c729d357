// OffscreenContext: an OpenGL 4 core context with no window (EGL) and the framebuffer it draws to.
#pragma once

#include <string>

#include "render/image.h"

namespace serosa::render {

/// An OpenGL >= 4.1 core context (4.5 when the driver has it) created through EGL without any
/// window system, plus a framebuffer object with a colour (RGBA8) and a depth (24-bit)
/// attachment, multisampled when `samples` > 1, that every draw goes to. GL functions are loaded
/// with libepoxy.
///
/// EGL displays are tried in order: eglGetPlatformDisplayEXT with EGL_PLATFORM_SURFACELESS_MESA
/// (Mesa, no X, no GPU needed: llvmpipe), then EGL_PLATFORM_DEVICE_EXT on each enumerated device
/// (NVIDIA's driver), then plain eglGetDisplay(EGL_DEFAULT_DISPLAY).
///
/// The context is current on the constructing thread afterwards; a render thread that takes it
/// over calls release_current() on the old thread and make_current() on its own. The GL objects
/// of every renderer using this context must be destroyed before it.
///
/// One OffscreenContext per process at a time: EGL display initialisation is not reference
/// counted by Mesa 22 (no EGL_KHR_display_reference), so destroying one context terminates the
/// display under any other.
class OffscreenContext {
 public:
  /// @param width, height  framebuffer size in pixels (> 0)
  /// @param samples        multisample anti-aliasing samples; 1 = none; clamped to GL_MAX_SAMPLES
  /// @throws std::runtime_error starting "no offscreen GL available:" and naming what failed (no
  ///         EGL display, no OpenGL 4.1+ core context, incomplete framebuffer)
  OffscreenContext(int width, int height, int samples = 4);
  ~OffscreenContext();
  OffscreenContext(const OffscreenContext&) = delete;
  OffscreenContext& operator=(const OffscreenContext&) = delete;
  OffscreenContext(OffscreenContext&&) = delete;
  OffscreenContext& operator=(OffscreenContext&&) = delete;

  /// Makes the context current on the calling thread. @throws std::runtime_error on failure
  void make_current();
  /// Detaches the context from the calling thread.
  void release_current();

  /// Reallocates the framebuffer's attachments when the size changes (content is lost).
  void resize(int width, int height);
  /// Binds the framebuffer for drawing and sets the viewport to its size.
  void bind_framebuffer();
  /// Resolves multisampling and reads the framebuffer back (glReadPixels), rows flipped so that
  /// the first row is the top of the picture.
  [[nodiscard]] Image read_image();
  /// Waits until every GL command issued so far has executed (glFinish): for timing draws.
  void finish();

  [[nodiscard]] int width() const { return width_; }
  [[nodiscard]] int height() const { return height_; }
  [[nodiscard]] int samples() const { return samples_; }
  /// GL_VERSION and GL_RENDERER strings, e.g. "4.5 (Core Profile) Mesa 22.3.6" and "llvmpipe ...".
  [[nodiscard]] const std::string& gl_version() const { return gl_version_; }
  [[nodiscard]] const std::string& gl_renderer() const { return gl_renderer_; }
  /// The EGL path that worked: "surfaceless", "device" or "default".
  [[nodiscard]] const std::string& egl_platform() const { return egl_platform_; }

 private:
  void create_framebuffer();
  void destroy_framebuffer();

  // EGL handles kept as void* so that this header needs no EGL or GL include.
  void* display_ = nullptr;
  void* context_ = nullptr;
  void* surface_ = nullptr;  // a 1x1 pbuffer, only when the display lacks surfaceless contexts
  int width_ = 0;
  int height_ = 0;
  int samples_ = 1;
  // GL object names (GLuint): the draw FBO (multisampled) and the single-sampled resolve FBO.
  unsigned int draw_fbo_ = 0;
  unsigned int draw_color_ = 0;
  unsigned int draw_depth_ = 0;
  unsigned int resolve_fbo_ = 0;
  unsigned int resolve_color_ = 0;
  std::string gl_version_;
  std::string gl_renderer_;
  std::string egl_platform_;
};

}  // namespace serosa::render
