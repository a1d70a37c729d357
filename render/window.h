// Window: the trainee's on-screen OpenGL 4 window (GLFW), the interactive twin of
// OffscreenContext. Owns the context; whoever draws into it must be on the thread that made it.
#pragma once

#include <string>

#include "render/image.h"

struct GLFWwindow;

namespace serosa::render {

/// Keys a session reacts to (GLFW key codes stay inside render/).
/// Space: pause; V: next view; Up/Down: tessellation; O: 0/30 degree scope; H: overlay on/off;
/// in a replay Left/Right: seek -/+ 1 s, Plus/Minus (main row or keypad): faster/slower.
enum class Key {
  kEscape,
  kSpace,
  kV,
  kUp,
  kDown,
  kO,
  kH,
  kLeft,
  kRight,
  kPlus,
  kMinus,
  kTab,     ///< the session's active instrument (mouse input)
  kW,       ///< insert the active instrument
  kS,       ///< retract it
  kQ,       ///< roll it counter-clockwise
  kE,       ///< roll it clockwise
  kJ,       ///< open/close its jaws
  kB,       ///< replay: branch here and take over with the mouse
  kI,       ///< insert the endoscope
  kK,       ///< retract it
  kComma,   ///< rotate it (the 30 degree optic sweeps the view) counter-clockwise
  kPeriod,  ///< clockwise
  kN,       ///< replay: jump to the next error on the timeline
  kP,       ///< press/release the active instrument's cautery pedal
  kCount
};

class Window {
 public:
  /// Opens a window with an OpenGL >= 4.1 core context, current on the calling thread.
  /// @throws std::runtime_error naming what failed (no display, no GL 4.1 core context)
  Window(int width, int height, const std::string& title);
  ~Window();
  Window(const Window&) = delete;
  Window& operator=(const Window&) = delete;
  Window(Window&&) = delete;
  Window& operator=(Window&&) = delete;

  /// True once the user closed the window (or close() was called).
  [[nodiscard]] bool should_close() const;
  void close();
  /// Processes pending window events; returns immediately.
  void poll_events();
  /// Shows what was drawn since the last swap.
  void swap_buffers();
  /// Binds the default framebuffer with the viewport covering it.
  void bind_framebuffer();
  /// Framebuffer size in pixels (differs from the window size on high-DPI screens).
  [[nodiscard]] int width() const;
  [[nodiscard]] int height() const;
  /// True when `key` went down since the previous call for that key.
  [[nodiscard]] bool pressed(Key key);
  void set_title(const std::string& title);
  /// Reads back the back buffer (what was drawn since the last swap), first row at the top.
  [[nodiscard]] Image read_image();
  /// The pointer's position in framebuffer pixels (origin top left; outside the window it may be
  /// negative or beyond the size).
  void cursor(float& x, float& y) const;
  /// True while the primary mouse button is held.
  [[nodiscard]] bool mouse_down() const;
  /// Whether the right mouse button is held.
  [[nodiscard]] bool right_mouse_down() const;

 private:
  GLFWwindow* m_window = nullptr;
  bool m_down[static_cast<int>(Key::kCount)] = {};
};

}  // namespace serosa::render
