#include "window/summary_screen.h"

#include <chrono>
#include <thread>

#include "render/png_writer.h"

namespace serosa::window {

void show_summary(render::Window& window, render::FrameRenderer& renderer,
                  const render::RenderFrame& frame, const render::SnapshotOptions& options,
                  render::Overlay& overlay, const render::SessionSummary& summary, double seconds,
                  const std::filesystem::path& snapshot, const std::atomic<bool>& interrupted) {
  using Clock = std::chrono::steady_clock;
  const auto start = Clock::now();
  window.set_title("Serosa  session summary");
  for (;;) {
    window.poll_events();
    const bool timed_out =
        seconds > 0.0 && std::chrono::duration<double>(Clock::now() - start).count() > seconds;
    // Esc ended the session and may still be held: Space leaves too, at its first press.
    const bool leave = window.pressed(render::Key::kEscape) ||
                       window.pressed(render::Key::kSpace) || window.should_close() ||
                       interrupted.load() || timed_out;
    window.bind_framebuffer();
    renderer.draw(frame, options, window.width(), window.height());
    overlay.draw_summary(summary, window.width(), window.height());
    if (leave && !snapshot.empty()) render::write_png(window.read_image(), snapshot);
    window.swap_buffers();
    if (leave) return;
    std::this_thread::sleep_for(std::chrono::milliseconds(50));  // a still picture: 20 frames/s
  }
}

}  // namespace serosa::window
