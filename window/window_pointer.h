// The trainee window's input in the mouse control's plain terms (window/pointer_control.h).
#pragma once

#include "render/render_frame.h"
#include "render/window.h"
#include "window/pointer_control.h"

namespace serosa::window {

/// The events the window gathered since the last call (render::Window::take_events), and whether
/// J is held now.
[[nodiscard]] PointerEvents pointer_events(render::Window& window);

/// The picture's right and up in the scene, for `camera` (unit, orthogonal to its view).
[[nodiscard]] ScreenAxes screen_axes(const render::Camera& camera);

}  // namespace serosa::window
