// The trainee window's input in the mouse control's plain terms (app/pointer_control.h).
#pragma once

#include "app/pointer_control.h"
#include "render/render_frame.h"
#include "render/window.h"

namespace serosa::app {

/// The events the window gathered since the last call (render::Window::take_events), and whether
/// J is held now.
[[nodiscard]] PointerEvents pointer_events(render::Window& window);

/// The picture's right and up in the scene, for `camera` (unit, orthogonal to its view).
[[nodiscard]] ScreenAxes screen_axes(const render::Camera& camera);

}  // namespace serosa::app
