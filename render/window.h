// Window: the trainee's on-screen OpenGL 4 window (GLFW), the interactive twin of
// OffscreenContext. Owns the context; whoever draws into it must be on the thread that made it.
#pragma once

#include <array>
#include <string>

#include "render/image.h"
#include "render/key_clock.h"

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
  kF1,      ///< the controls panel (as H)
  kF2,      ///< the overlay on/off (the session; H there shows the controls)
  kHome,    ///< bring the active instrument back into view
  kX,       ///< exchange the active hand's instrument for the next waiting in its port
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
  /// True when `key` went down since the previous call for that key: each tap the callbacks saw
  /// once, however many fell between two calls (two quick taps are two presses, a frame apart).
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

  /// Input gathered event by event since the previous take (GLFW callbacks, during
  /// poll_events): nothing a slow frame would miss between two reads of the pointer and keys.
  struct Events {
    float drag_dx_px = 0.0f;    ///< pointer motion with the left button held, framebuffer px
    float drag_dy_px = 0.0f;    ///< (+ = down)
    float scroll_steps = 0.0f;  ///< wheel steps (+ = away from the user)
    std::array<int, static_cast<int>(Key::kCount)> presses{};  ///< times each key went down
    /// For each key let go since the previous take, how long it had surely been down, s
    /// (KeyClock: a slow frame does not stretch a tap); < 0: not let go.
    std::array<double, static_cast<int>(Key::kCount)> released_after_s{};
    Events() { released_after_s.fill(-1.0); }
  };
  /// What was gathered since the previous call, and starts gathering anew.
  [[nodiscard]] Events take_events();
  /// Whether `key` is held now.
  [[nodiscard]] bool key_down(Key key) const;
  /// How long `key` has been held, s, since the poll that delivered its press; < 0 when it is up.
  [[nodiscard]] double key_held_s(Key key) const;

 private:
  static void on_key(GLFWwindow* w, int key, int scancode, int action, int mods);
  static void on_cursor(GLFWwindow* w, double x, double y);
  static void on_button(GLFWwindow* w, int button, int action, int mods);
  static void on_scroll(GLFWwindow* w, double dx, double dy);

  GLFWwindow* m_window = nullptr;
  std::array<int, static_cast<int>(Key::kCount)> m_taps{};  // presses pressed() has not told
  Events m_events;
  KeyClock m_keys{static_cast<std::size_t>(Key::kCount)};  // as the callbacks saw the keys
  bool m_left_held = false;  // the left button, as the callbacks saw it
  double m_cursor_x = 0.0;   // the pointer when the callbacks saw it last, window coordinates
  double m_cursor_y = 0.0;
};

}  // namespace serosa::render
