// The summary screen at the end of `serosa run`: the session's assessment over its last picture.
#pragma once

#include <atomic>
#include <filesystem>

#include "render/frame_renderer.h"
#include "render/overlay.h"
#include "render/render_frame.h"
#include "render/session_summary.h"
#include "render/window.h"

namespace serosa::window {

/// Draws `frame` with the summary over it (the window's title says so) until the trainee leaves
/// (Esc or Space pressed, the window closed,
/// `interrupted`) or, when `seconds` > 0, that much wall time passed; writes the last picture to
/// `snapshot` when it is not empty.
void show_summary(render::Window& window, render::FrameRenderer& renderer,
                  const render::RenderFrame& frame, const render::SnapshotOptions& options,
                  render::Overlay& overlay, const render::SessionSummary& summary, double seconds,
                  const std::filesystem::path& snapshot, const std::atomic<bool>& interrupted);

}  // namespace serosa::window
