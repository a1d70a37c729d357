// The window's pointer and keys as the mouse device's cumulative input (window thread only), in
// the picture's terms: a drag with the left button moves the active instrument's tip the way the
// pointer went in the picture, kDragMetresPerPixel per pixel whatever its insertion (the camera's
// right and up turn pixels into scene metres, haptics/mouse_device.h carries it through the
// trocar); W/S move it into and out of the picture by kDepthMetresPerStep (along the view, so
// that depth in the picture is one key whichever way the shaft points), the wheel pushes it in
// and pulls it back along its shaft, Q/E roll it, Home brings it back into view,
// P presses or releases its cautery pedal (a hook's current), Tab makes the other hand active,
// X exchanges the active hand's instrument (haptics/hand_rack.h).
// J works the jaws as a hand does: a tap (shorter than kJawTapS) opens jaws that are at most half
// open, fully, and closes the others; held longer, it closes them steadily (a bite), from full
// to closed in kJawCloseS, and they stay where they are when it is let go.
// Input is gathered event by event between frames (render::Window::Events), so a slow frame
// loses no drag and no key press.
#pragma once

#include <array>
#include <cstddef>

#include "engine/math.h"
#include "haptics/mouse_device.h"

namespace serosa::window {

/// Tip motion per pixel of drag, m (0.1 mm: the 1280-pixel picture spans 13 cm of motion).
inline constexpr double kDragMetresPerPixel = 1e-4;
/// W/S: tip motion into (W) or out of (S) the picture per press, m.
inline constexpr double kDepthMetresPerStep = 0.003;
/// A J press released sooner than this is a tap, s.
inline constexpr double kJawTapS = 0.25;
/// Held J closes fully open jaws in this long, s.
inline constexpr double kJawCloseS = 1.5;

/// The picture's directions in the scene, unit vectors: right and up on the screen, and into it.
struct ScreenAxes {
  Vec3 right = Vec3::UnitX();
  Vec3 up = Vec3::UnitY();
  Vec3 forward = -Vec3::UnitZ();
};

/// What the window gathered since the last frame, in plain terms (no GLFW).
struct PointerEvents {
  double drag_dx_px = 0.0;  ///< left-button drag, px (+ = right)
  double drag_dy_px = 0.0;  ///< px (+ = down)
  double scroll_steps = 0.0;
  int tab = 0, insert = 0, retract = 0, roll_left = 0, roll_right = 0, pedal = 0, home = 0;
  int exchange = 0;         ///< presses of X: the active hand's instrument exchange
  int jaw_presses = 0;      ///< times J went down
  bool jaw_held = false;    ///< J is down now
  double jaw_held_s = 0.0;  ///< how long J has been down, s (when jaw_held)
  /// J was let go since the last frame after being down this long, s; < 0: it was not. Timed
  /// by the key events themselves, so a slow frame between press and release is still a tap.
  double jaw_released_after_s = -1.0;
};

class PointerControl {
 public:
  explicit PointerControl(const haptics::PointerInput& start = {}) : m_input(start) {}

  /// Takes one frame's events and the picture's axes as the trainee saw it; returns the
  /// cumulative input.
  const haptics::PointerInput& update(const PointerEvents& e, const ScreenAxes& axes);

  [[nodiscard]] std::size_t active() const noexcept { return m_active; }
  [[nodiscard]] const haptics::PointerInput& input() const noexcept { return m_input; }

 private:
  void update_jaw(const PointerEvents& e);

  haptics::PointerInput m_input;
  std::size_t m_active = 0;
  bool m_jaw_holding = false;  // J went down and has not been let go (as the frames saw it)
  double m_jaw_start = 0.0;    // the jaw fraction when it went down
};

}  // namespace serosa::window
