#include "app/session.h"

#include <spdlog/spdlog.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <string>

#include "app/assemble_state.h"
#include "app/compose.h"
#include "app/render_frame_from_surface.h"
#include "engine/scene.h"
#include "render/camera.h"
#include "render/frame_renderer.h"
#include "render/window.h"
#include "surface/extract_surface.h"

namespace serosa::app {

int run_session(const std::filesystem::path& scene_path, double seconds) {
  using Clock = std::chrono::steady_clock;
  const Scene scene = load_scene(scene_path);
  AssembledScene assembled = assemble_state(scene);
  Composition comp = compose(scene, assembled);
  SimState& state = assembled.state;
  for (Effect e : comp.unavailable)
    spdlog::warn("effect '{}' is not implemented in this build: not simulated", effect_name(e));

  render::Window window(scene.render.width, scene.render.height, "Serosa");
  render::FrameRenderer renderer;
  render::SnapshotOptions options;
  options.tessellation = scene.render.tessellation;
  options.shape_factor = static_cast<float>(scene.render.shape_factor);
  const auto names = assembled.group_names();
  const bool need_edges = true;

  surface::SurfaceMesh surf = surface::extract_surface(state.mesh);
  render::RenderFrame frame;
  fill_render_frame(state.mesh, surf, names, need_edges, frame);
  frame.camera = render::auto_camera(
      frame, static_cast<float>(window.width()) / static_cast<float>(std::max(window.height(), 1)));
  const render::Camera camera = frame.camera;

  const double dt = scene.settings.dt_s;
  const auto start = Clock::now();
  auto last = start;
  double owed_s = 0.0;  // simulated time the solver is behind the wall clock
  bool paused = false;
  int view = 0;
  double step_ms = 0.0;
  while (!window.should_close()) {
    window.poll_events();
    if (window.pressed(render::Key::kEscape)) window.close();
    if (window.pressed(render::Key::kSpace)) paused = !paused;
    if (window.pressed(render::Key::kV)) view = (view + 1) % 3;
    if (window.pressed(render::Key::kUp))
      options.tessellation = std::min(options.tessellation + 1, 16);
    if (window.pressed(render::Key::kDown))
      options.tessellation = std::max(options.tessellation - 1, 1);
    options.view = static_cast<render::SnapshotOptions::View>(view);

    const auto now = Clock::now();
    if (seconds > 0.0 && std::chrono::duration<double>(now - start).count() > seconds) break;
    owed_s = paused ? 0.0 : owed_s + std::chrono::duration<double>(now - last).count();
    last = now;
    int steps = 0;
    const auto s0 = Clock::now();
    while (owed_s >= dt && steps < 8) {
      comp.runner->step(state);
      owed_s -= dt;
      ++steps;
    }
    const bool slow = owed_s >= dt;
    if (slow) owed_s = 0.0;  // drop what cannot be caught up: slow motion, not a spiral
    if (steps > 0)
      step_ms = std::chrono::duration<double, std::milli>(Clock::now() - s0).count() / steps;

    if (surf.topology_version != state.mesh.topology_version)
      surf = surface::extract_surface(state.mesh);
    fill_render_frame(state.mesh, surf, names, need_edges, frame);
    frame.camera = camera;
    window.bind_framebuffer();
    renderer.draw(frame, options, window.width(), window.height());
    window.swap_buffers();

    char title[160];
    static constexpr const char* kViews[] = {"visual", "collision", "mechanical"};
    std::snprintf(title, sizeof title, "Serosa  t=%.2f s  FEM %.2f ms/step  %s  tess %d%s%s",
                  state.time_s, step_ms, kViews[view], options.tessellation,
                  paused ? "  [paused]" : "", slow ? "  [slow motion]" : "");
    window.set_title(title);
  }
  return 0;
}

}  // namespace serosa::app
