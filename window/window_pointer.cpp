#include "window/window_pointer.h"

namespace serosa::window {

PointerEvents pointer_events(render::Window& window) {
  const render::Window::Events w = window.take_events();
  const auto n = [&w](render::Key k) { return w.presses[static_cast<std::size_t>(k)]; };
  PointerEvents e;
  e.drag_dx_px = w.drag_dx_px;
  e.drag_dy_px = w.drag_dy_px;
  e.scroll_steps = w.scroll_steps;
  e.tab = n(render::Key::kTab);
  e.insert = n(render::Key::kW);
  e.retract = n(render::Key::kS);
  e.roll_left = n(render::Key::kQ);
  e.roll_right = n(render::Key::kE);
  e.pedal = n(render::Key::kP);
  e.home = n(render::Key::kHome);
  e.exchange = n(render::Key::kX);
  e.jaw_presses = n(render::Key::kJ);
  e.jaw_held_s = window.key_held_s(render::Key::kJ);
  e.jaw_held = e.jaw_held_s >= 0.0;
  e.jaw_released_after_s = w.released_after_s[static_cast<std::size_t>(render::Key::kJ)];
  return e;
}

ScreenAxes screen_axes(const render::Camera& camera) {
  const Vec3 eye(camera.eye[0], camera.eye[1], camera.eye[2]);
  const Vec3 target(camera.target[0], camera.target[1], camera.target[2]);
  const Vec3 up(camera.up[0], camera.up[1], camera.up[2]);
  ScreenAxes a;
  const Vec3 forward = target - eye;
  const Vec3 right = forward.cross(up);
  if (forward.norm() < 1e-12 || right.norm() < 1e-12) return a;
  a.right = right.normalized();
  a.forward = forward.normalized();
  a.up = a.right.cross(a.forward);
  return a;
}

}  // namespace serosa::window
