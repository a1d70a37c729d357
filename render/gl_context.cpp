// OffscreenContext: EGL display and context, the framebuffer, readback (see gl_context.h).
#include "render/gl_context.h"

// epoxy must come before any other GL header.
#include <epoxy/gl.h>
// EGL itself is called directly (libEGL); its extension entry points through eglGetProcAddress,
// so that a missing extension is a null pointer and a clear error, not an abort inside epoxy.
#include <EGL/egl.h>
#include <EGL/eglext.h>

#include <algorithm>
#include <array>
#include <cstring>
#include <stdexcept>
#include <string_view>
#include <utility>
#include <vector>

namespace serosa::render {
namespace {

constexpr std::string_view kNoGl = "no offscreen GL available: ";

std::string egl_error_name(EGLint e) {
  switch (e) {
    case EGL_SUCCESS:
      return "EGL_SUCCESS";
    case EGL_NOT_INITIALIZED:
      return "EGL_NOT_INITIALIZED";
    case EGL_BAD_ACCESS:
      return "EGL_BAD_ACCESS";
    case EGL_BAD_ALLOC:
      return "EGL_BAD_ALLOC";
    case EGL_BAD_ATTRIBUTE:
      return "EGL_BAD_ATTRIBUTE";
    case EGL_BAD_CONFIG:
      return "EGL_BAD_CONFIG";
    case EGL_BAD_CONTEXT:
      return "EGL_BAD_CONTEXT";
    case EGL_BAD_CURRENT_SURFACE:
      return "EGL_BAD_CURRENT_SURFACE";
    case EGL_BAD_DISPLAY:
      return "EGL_BAD_DISPLAY";
    case EGL_BAD_MATCH:
      return "EGL_BAD_MATCH";
    case EGL_BAD_NATIVE_PIXMAP:
      return "EGL_BAD_NATIVE_PIXMAP";
    case EGL_BAD_NATIVE_WINDOW:
      return "EGL_BAD_NATIVE_WINDOW";
    case EGL_BAD_PARAMETER:
      return "EGL_BAD_PARAMETER";
    case EGL_BAD_SURFACE:
      return "EGL_BAD_SURFACE";
    case EGL_CONTEXT_LOST:
      return "EGL_CONTEXT_LOST";
    default:
      return "EGL error " + std::to_string(e);
  }
}

// True when the space-separated extension list `list` contains `name`.
bool has_extension(const char* list, std::string_view name) {
  if (list == nullptr) return false;
  std::string_view s(list);
  while (!s.empty()) {
    const std::size_t end = s.find(' ');
    if (s.substr(0, end) == name) return true;
    if (end == std::string_view::npos) break;
    s.remove_prefix(end + 1);
  }
  return false;
}

// Initialises `dpy`; on success returns true, else appends why to `log` and returns false.
bool try_initialize(EGLDisplay dpy, std::string_view what, std::string& log) {
  if (dpy == EGL_NO_DISPLAY) {
    log += std::string(what) + ": no display (" + egl_error_name(eglGetError()) + "); ";
    return false;
  }
  EGLint major = 0;
  EGLint minor = 0;
  if (eglInitialize(dpy, &major, &minor) != EGL_TRUE) {
    log += std::string(what) + ": eglInitialize failed (" + egl_error_name(eglGetError()) + "); ";
    return false;
  }
  return true;
}

// The first EGL display that initialises, and which path gave it.
std::pair<EGLDisplay, std::string> open_display() {
  std::string log;
  const char* client = eglQueryString(EGL_NO_DISPLAY, EGL_EXTENSIONS);
  const auto get_platform_display = reinterpret_cast<PFNEGLGETPLATFORMDISPLAYEXTPROC>(
      eglGetProcAddress("eglGetPlatformDisplayEXT"));
  const bool platform_base =
      has_extension(client, "EGL_EXT_platform_base") && get_platform_display != nullptr;

  // 1. Mesa's surfaceless platform: no window system and no device node needed.
  if (platform_base && has_extension(client, "EGL_MESA_platform_surfaceless")) {
    EGLDisplay dpy =
        get_platform_display(EGL_PLATFORM_SURFACELESS_MESA, EGL_DEFAULT_DISPLAY, nullptr);
    if (try_initialize(dpy, "surfaceless", log)) return {dpy, "surfaceless"};
  } else {
    log += "surfaceless: EGL_MESA_platform_surfaceless not offered; ";
  }

  // 2. An EGL device (NVIDIA's driver, or Mesa's software device).
  const auto query_devices =
      reinterpret_cast<PFNEGLQUERYDEVICESEXTPROC>(eglGetProcAddress("eglQueryDevicesEXT"));
  if (platform_base && has_extension(client, "EGL_EXT_platform_device") &&
      query_devices != nullptr) {
    std::array<EGLDeviceEXT, 16> devices{};
    EGLint count = 0;
    if (query_devices(static_cast<EGLint>(devices.size()), devices.data(), &count) == EGL_TRUE) {
      for (EGLint i = 0; i < count; ++i) {
        EGLDisplay dpy = get_platform_display(EGL_PLATFORM_DEVICE_EXT, devices[i], nullptr);
        if (try_initialize(dpy, "device " + std::to_string(i), log)) return {dpy, "device"};
      }
      if (count == 0) log += "device: no EGL devices; ";
    } else {
      log += "device: eglQueryDevicesEXT failed (" + egl_error_name(eglGetError()) + "); ";
    }
  } else {
    log += "device: EGL_EXT_platform_device not offered; ";
  }

  // 3. Whatever the default display is (X11 or Wayland when there is one; EGL_PLATFORM=...).
  EGLDisplay dpy = eglGetDisplay(EGL_DEFAULT_DISPLAY);
  if (try_initialize(dpy, "default", log)) return {dpy, "default"};

  throw std::runtime_error(std::string(kNoGl) + "no EGL display (" + log + ")");
}

// An EGL config for desktop OpenGL with 8-bit colour; pbuffer-capable when possible.
EGLConfig choose_config(EGLDisplay dpy) {
  for (const bool pbuffer : {true, false}) {
    std::vector<EGLint> attribs{EGL_RENDERABLE_TYPE, EGL_OPENGL_BIT,
                                EGL_RED_SIZE,        8,
                                EGL_GREEN_SIZE,      8,
                                EGL_BLUE_SIZE,       8,
                                EGL_ALPHA_SIZE,      8};
    if (pbuffer) attribs.insert(attribs.end(), {EGL_SURFACE_TYPE, EGL_PBUFFER_BIT});
    attribs.push_back(EGL_NONE);
    EGLConfig config = nullptr;
    EGLint n = 0;
    if (eglChooseConfig(dpy, attribs.data(), &config, 1, &n) == EGL_TRUE && n > 0) return config;
  }
  throw std::runtime_error(std::string(kNoGl) + "no EGL config for desktop OpenGL (" +
                           egl_error_name(eglGetError()) + ")");
}

// A core-profile context of the highest version from 4.5 down to 4.1 the driver gives.
EGLContext create_context(EGLDisplay dpy, EGLConfig config, const std::string& platform) {
  if (eglBindAPI(EGL_OPENGL_API) != EGL_TRUE) {
    throw std::runtime_error(std::string(kNoGl) + "no desktop OpenGL API on EGL " + platform +
                             " (" + egl_error_name(eglGetError()) + ")");
  }
  std::string log;
  for (int minor = 5; minor >= 1; --minor) {
    const std::array<EGLint, 7> attribs{EGL_CONTEXT_MAJOR_VERSION,
                                        4,
                                        EGL_CONTEXT_MINOR_VERSION,
                                        minor,
                                        EGL_CONTEXT_OPENGL_PROFILE_MASK,
                                        EGL_CONTEXT_OPENGL_CORE_PROFILE_BIT,
                                        EGL_NONE};
    EGLContext ctx = eglCreateContext(dpy, config, EGL_NO_CONTEXT, attribs.data());
    if (ctx != EGL_NO_CONTEXT) return ctx;
    log += "4." + std::to_string(minor) + ": " + egl_error_name(eglGetError()) + "; ";
  }
  throw std::runtime_error(std::string(kNoGl) + "no OpenGL 4.1+ core context on EGL " + platform +
                           " (" + log + ")");
}

std::string gl_string(GLenum name) {
  const auto* s = reinterpret_cast<const char*>(glGetString(name));
  return s != nullptr ? std::string(s) : std::string();
}

}  // namespace

OffscreenContext::OffscreenContext(int width, int height, int samples)
    : width_(width), height_(height), samples_(std::max(samples, 1)) {
  if (width <= 0 || height <= 0) {
    throw std::invalid_argument("OffscreenContext: size must be positive, got " +
                                std::to_string(width) + "x" + std::to_string(height));
  }
  auto [dpy, platform] = open_display();
  display_ = dpy;
  egl_platform_ = std::move(platform);
  try {
    const EGLConfig config = choose_config(dpy);
    context_ = create_context(dpy, config, egl_platform_);
    // Surfaceless when the display allows it, else a tiny pbuffer that is never drawn to.
    if (!has_extension(eglQueryString(dpy, EGL_EXTENSIONS), "EGL_KHR_surfaceless_context")) {
      const std::array<EGLint, 5> pb{EGL_WIDTH, 1, EGL_HEIGHT, 1, EGL_NONE};
      surface_ = eglCreatePbufferSurface(dpy, config, pb.data());
      if (surface_ == EGL_NO_SURFACE) {
        throw std::runtime_error(std::string(kNoGl) + "no surfaceless context and no pbuffer (" +
                                 egl_error_name(eglGetError()) + ")");
      }
    }
    make_current();
    if (!epoxy_is_desktop_gl() || epoxy_gl_version() < 41) {
      throw std::runtime_error(std::string(kNoGl) + "the context is not desktop OpenGL 4.1+ (" +
                               gl_string(GL_VERSION) + ")");
    }
    gl_version_ = gl_string(GL_VERSION);
    gl_renderer_ = gl_string(GL_RENDERER);
    create_framebuffer();
  } catch (...) {
    if (context_ != nullptr) {
      eglMakeCurrent(dpy, EGL_NO_SURFACE, EGL_NO_SURFACE, EGL_NO_CONTEXT);
      eglDestroyContext(dpy, context_);
    }
    if (surface_ != nullptr) eglDestroySurface(dpy, surface_);
    eglTerminate(dpy);
    throw;
  }
}

OffscreenContext::~OffscreenContext() {
  if (eglMakeCurrent(display_, surface_, surface_, context_) == EGL_TRUE) destroy_framebuffer();
  eglMakeCurrent(display_, EGL_NO_SURFACE, EGL_NO_SURFACE, EGL_NO_CONTEXT);
  eglDestroyContext(display_, context_);
  if (surface_ != nullptr) eglDestroySurface(display_, surface_);
  eglTerminate(display_);
  eglReleaseThread();
}

void OffscreenContext::make_current() {
  if (eglMakeCurrent(display_, surface_, surface_, context_) != EGL_TRUE) {
    throw std::runtime_error("OffscreenContext: eglMakeCurrent failed (" +
                             egl_error_name(eglGetError()) + ")");
  }
}

void OffscreenContext::release_current() {
  eglMakeCurrent(display_, EGL_NO_SURFACE, EGL_NO_SURFACE, EGL_NO_CONTEXT);
}

void OffscreenContext::create_framebuffer() {
  GLint max_samples = 1;
  glGetIntegerv(GL_MAX_SAMPLES, &max_samples);
  samples_ = std::clamp(samples_, 1, std::max(max_samples, 1));

  // The draw target: colour and depth renderbuffers, multisampled when samples_ > 1.
  glGenFramebuffers(1, &draw_fbo_);
  glGenRenderbuffers(1, &draw_color_);
  glGenRenderbuffers(1, &draw_depth_);
  glBindRenderbuffer(GL_RENDERBUFFER, draw_color_);
  glRenderbufferStorageMultisample(GL_RENDERBUFFER, samples_ > 1 ? samples_ : 0, GL_RGBA8, width_,
                                   height_);
  glBindRenderbuffer(GL_RENDERBUFFER, draw_depth_);
  glRenderbufferStorageMultisample(GL_RENDERBUFFER, samples_ > 1 ? samples_ : 0,
                                   GL_DEPTH_COMPONENT24, width_, height_);
  glBindFramebuffer(GL_FRAMEBUFFER, draw_fbo_);
  glFramebufferRenderbuffer(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_RENDERBUFFER, draw_color_);
  glFramebufferRenderbuffer(GL_FRAMEBUFFER, GL_DEPTH_ATTACHMENT, GL_RENDERBUFFER, draw_depth_);
  GLenum status = glCheckFramebufferStatus(GL_FRAMEBUFFER);

  // The resolve target: single-sampled colour that glReadPixels reads.
  glGenFramebuffers(1, &resolve_fbo_);
  glGenRenderbuffers(1, &resolve_color_);
  glBindRenderbuffer(GL_RENDERBUFFER, resolve_color_);
  glRenderbufferStorage(GL_RENDERBUFFER, GL_RGBA8, width_, height_);
  glBindFramebuffer(GL_FRAMEBUFFER, resolve_fbo_);
  glFramebufferRenderbuffer(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_RENDERBUFFER, resolve_color_);
  if (status == GL_FRAMEBUFFER_COMPLETE) status = glCheckFramebufferStatus(GL_FRAMEBUFFER);
  glBindRenderbuffer(GL_RENDERBUFFER, 0);
  glBindFramebuffer(GL_FRAMEBUFFER, 0);
  if (status != GL_FRAMEBUFFER_COMPLETE) {
    destroy_framebuffer();
    throw std::runtime_error(std::string(kNoGl) + "framebuffer incomplete (status 0x" +
                             std::to_string(status) + ") at " + std::to_string(width_) + "x" +
                             std::to_string(height_) + ", " + std::to_string(samples_) +
                             " samples");
  }
}

void OffscreenContext::destroy_framebuffer() {
  const std::array<GLuint, 2> fbos{draw_fbo_, resolve_fbo_};
  const std::array<GLuint, 3> rbs{draw_color_, draw_depth_, resolve_color_};
  glDeleteFramebuffers(static_cast<GLsizei>(fbos.size()), fbos.data());
  glDeleteRenderbuffers(static_cast<GLsizei>(rbs.size()), rbs.data());
  draw_fbo_ = draw_color_ = draw_depth_ = resolve_fbo_ = resolve_color_ = 0;
}

void OffscreenContext::resize(int width, int height) {
  if (width <= 0 || height <= 0) {
    throw std::invalid_argument("OffscreenContext::resize: size must be positive");
  }
  if (width == width_ && height == height_) return;
  destroy_framebuffer();
  width_ = width;
  height_ = height;
  create_framebuffer();
}

void OffscreenContext::bind_framebuffer() {
  glBindFramebuffer(GL_FRAMEBUFFER, draw_fbo_);
  glViewport(0, 0, width_, height_);
}

void OffscreenContext::finish() { glFinish(); }

Image OffscreenContext::read_image() {
  // Resolve the multisampled colour into the single-sampled target.
  glBindFramebuffer(GL_READ_FRAMEBUFFER, draw_fbo_);
  glBindFramebuffer(GL_DRAW_FRAMEBUFFER, resolve_fbo_);
  glBlitFramebuffer(0, 0, width_, height_, 0, 0, width_, height_, GL_COLOR_BUFFER_BIT, GL_NEAREST);
  glBindFramebuffer(GL_READ_FRAMEBUFFER, resolve_fbo_);
  glPixelStorei(GL_PACK_ALIGNMENT, 1);

  Image img;
  img.width = width_;
  img.height = height_;
  const std::size_t row = 4 * static_cast<std::size_t>(width_);
  std::vector<std::uint8_t> bottom_up(row * static_cast<std::size_t>(height_));
  glReadPixels(0, 0, width_, height_, GL_RGBA, GL_UNSIGNED_BYTE, bottom_up.data());
  glBindFramebuffer(GL_FRAMEBUFFER, 0);
  const GLenum err = glGetError();
  if (err != GL_NO_ERROR) {
    throw std::runtime_error("OffscreenContext::read_image: GL error " + std::to_string(err));
  }
  // GL's first row is the bottom of the picture; PNG's is the top.
  img.rgba.resize(bottom_up.size());
  for (std::size_t y = 0; y < static_cast<std::size_t>(height_); ++y) {
    std::memcpy(img.rgba.data() + y * row,
                bottom_up.data() + (static_cast<std::size_t>(height_) - 1 - y) * row, row);
  }
  return img;
}

}  // namespace serosa::render
