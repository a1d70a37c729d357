#include "app/session.h"

#include <spdlog/spdlog.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cstdio>
#include <exception>
#include <optional>
#include <string>
#include <thread>

#include <fstream>

#include "app/assemble_state.h"
#include "app/assessment_report.h"
#include "app/compose.h"
#include "app/drawn_surface.h"
#include "app/headless.h"
#include "app/instrument_devices.h"
#include "app/output_paths.h"
#include "app/render_frame_from_surface.h"
#include "app/scenery_from_scene.h"
#include "app/session_summary.h"
#include "app/simulation.h"
#include "engine/hook.h"
#include "engine/input_error.h"
#include "engine/scene/scene.h"
#include "engine/triple_buffer.h"
#include "haptics/haptic_loop.h"
#include "haptics/haptics_stage.h"
#include "haptics/mouse_device.h"
#include "haptics/usb_rig.h"
#include "metrics/metrics_stage.h"
#include "recording/record_stage.h"
#include "recording/recording_writer.h"
#include "render/camera.h"
#include "render/frame_renderer.h"
#include "render/image_stats.h"
#include "render/overlay.h"
#include "render/png_writer.h"
#include "render/renderer_threads.h"
#include "render/scaled_target.h"
#include "render/window.h"
#include "surface/cut_faces.h"
#include "trainee/help_seen.h"
#include "window/frame_pacer.h"
#include "window/hand_overlay.h"
#include "window/overlay_stats.h"
#include "window/pointer_control.h"
#include "window/scope_control.h"
#include "window/summary_screen.h"
#include "window/view_log.h"
#include "window/window_interrupt.h"
#include "window/window_pointer.h"

namespace serosa::app {
namespace {

// The trainee window draws at most this many frames a second (window/frame_pacer.h).
constexpr double kMaxFramesPerS = 60.0;

using Clock = std::chrono::steady_clock;
/// The least time between two frames the solver publishes (the window's frame rate cap).
constexpr auto kPublishPeriod = std::chrono::duration_cast<Clock::duration>(
    std::chrono::duration<double>(1.0 / kMaxFramesPerS));

// What the window thread tells the solver thread.
struct Control {
  std::atomic<bool> paused{false};
  std::atomic<std::size_t> active_handle{0};  // the mouse's active hand (window thread writes)
  std::atomic<bool> finished{false};  // set by the solver thread when it stops (error or stop)
};

// The solver thread: fixed dt, paced to real time, one published frame per step, stepping the
// headless driver.
class SolverLoop {
 public:
  SolverLoop(Simulation& sim, float aspect, TripleBuffer<render::RenderFrame>& frames,
             Control& control)
      : m_scene(sim.scene()),
        m_sim(sim),
        m_state(sim.state()),
        m_comp(sim.composition()),
        m_names(drawn_group_names(sim.scene(), sim.assembled().group_names())),
        m_aspect(aspect),
        m_frames(frames),
        m_control(control) {}

  void run(const std::stop_token& stop) {
    try {
      loop(stop);
    } catch (...) {
      m_error = std::current_exception();
    }
    m_control.finished.store(true);
  }

  [[nodiscard]] std::exception_ptr error() const { return m_error; }
  [[nodiscard]] std::int64_t steps() const { return m_steps; }
  /// Whether the last frame published was the endoscope's view (read once the loop has stopped).
  [[nodiscard]] bool through_scope() const { return m_through_scope; }

 private:
  void loop(const std::stop_token& stop) {
    m_drawn.emplace(m_state.mesh);  // the uncut mesh: the wound reference
    m_scenery = scenery_from_scene(m_scene, m_state.mesh);
    m_version = m_state.mesh.topology_version;
    publish();  // the driver prepared the first step before the clock starts
    const auto dt = std::chrono::duration_cast<Clock::duration>(
        std::chrono::duration<double>(m_scene.settings.dt_s));
    // The state at simulated time t is published no earlier than wall time t: each step starts
    // one dt after the one before (the first one dt after the start, or after a pause), so the
    // trainee never sees the solver ahead of the clock.
    auto next = Clock::now() + dt;
    auto rate_start = Clock::now();
    int rate_steps = 0;
    while (!stop.stop_requested()) {
      if (m_control.paused.load()) {
        std::this_thread::sleep_for(std::chrono::milliseconds(20));
        next = Clock::now() + dt;
        publish();  // the overlay shows the pause; the scope may have turned
        continue;
      }
      std::this_thread::sleep_until(next);  // returns at once when behind
      if (stop.stop_requested()) break;
      m_sim.step();
      const double ms = m_sim.step_ms().back();
      m_step_ms = m_step_ms == 0.0 ? ms : 0.9 * m_step_ms + 0.1 * ms;
      ++rate_steps;
      const auto now = Clock::now();
      ++m_steps;
      if (now - rate_start >= std::chrono::seconds(1)) {
        m_rate_hz = rate_steps / std::chrono::duration<double>(now - rate_start).count();
        rate_start = now;
        rate_steps = 0;
      }
      count_cuts();
      // The window draws at most kMaxFramesPerS: a frame published sooner after the last than
      // that would be overwritten unseen, and filling one (the surface's split normals) cost the
      // solver's core more than a tenth of its time at one a step.
      if (now - m_published >= kPublishPeriod) publish();
      // More than 0.1 s behind, drop the debt (slow motion rather than a catch-up spiral).
      next += dt;
      const auto after = Clock::now();
      // Slow motion: a whole step behind the clock. A step that ends a little after its time
      // (the renderer's threads had the core) is made up by the next one's sleep.
      m_slow = after > next + dt;
      if (after > next + std::chrono::milliseconds(100)) next = after;
    }
  }

  void count_cuts() {
    if (m_version != m_state.mesh.topology_version) {
      m_version = m_state.mesh.topology_version;
      ++m_cuts;
    }
  }

  void publish() {
    m_published = Clock::now();
    count_cuts();
    render::RenderFrame& f = m_frames.back();
    fill_render_frame(m_state.mesh, m_drawn->of(m_state), m_names, true, f,
                      &m_state.blocks.cutting.coagulated, m_state.blocks.cutting.coagulated_version,
                      &m_state.blocks.bleeding.stain);
    fill_render_tools(m_scene, m_state, f);
    // Each of the triple buffer's slots takes the scenery and the taeniae once; they never change.
    if (f.scenery.version != m_scenery.version) {
      f.scenery = m_scenery;
      fill_taenia(m_state.mesh, m_names, f);
    }
    std::optional<render::Camera> cam = endoscope_view(m_scene, m_state);
    m_through_scope = cam.has_value();
    if (!cam) {
      // No endoscope: a fixed camera fitted to the organs at the start.
      if (!m_fitted) m_fitted = render::auto_camera(f, m_aspect);
      cam = m_fitted;
    }
    f.camera = *cam;
    window::FrameStats stats;
    stats.sim_time_s = m_state.time_s;
    stats.fem_ms_per_step = m_step_ms;
    stats.solver_rate_hz = m_rate_hz;
    stats.real_time_factor = m_rate_hz * m_scene.settings.dt_s;
    // The haptic loop's telemetry is the loop thread's while it runs: the overlay's rate comes
    // from its live status (ticks per wall second over the last half second or more).
    stats.haptics = nullptr;
    if (m_comp.haptics != nullptr) {
      const auto now = Clock::now();
      const std::uint64_t tick = m_comp.haptics->status().tick;
      if (!m_hap_started) {
        m_hap_t0 = now;
        m_hap_tick0 = tick;
        m_hap_started = true;
      } else if (now - m_hap_t0 >= std::chrono::milliseconds(500)) {
        m_hap_rate_hz = static_cast<double>(tick - m_hap_tick0) /
                        std::chrono::duration<double>(now - m_hap_t0).count();
        m_hap_t0 = now;
        m_hap_tick0 = tick;
      }
      stats.haptic_live_rate_hz = m_hap_rate_hz;
    }
    stats.instruments = window::instruments_label(
        m_comp.haptics != nullptr ? std::optional<DeviceKind>(m_comp.haptics->device_kind())
                                  : std::nullopt,
        m_comp.haptics != nullptr && m_comp.haptics->device_connected(), m_comp.tools != nullptr,
        m_comp.haptics != nullptr && m_comp.haptics->rig_was_connected());
    stats.cuts = m_cuts;
    stats.paused = m_control.paused.load();
    stats.slow_motion = m_slow;
    f.overlay = window::overlay_data(stats);
    if (m_comp.haptics != nullptr && m_comp.haptics->device_kind() != DeviceKind::kScript) {
      const window::HandleTools& handles = m_comp.haptics->handle_tools();
      const std::size_t active = m_control.active_handle.load();
      const bool mouse = m_comp.haptics->device_kind() == DeviceKind::kMouse;
      window::mark_active_tool(f,
                               mouse && active < handles.size() ? handles[active] : std::nullopt);
      f.overlay.hands =
          window::overlay_hands(m_scene, m_state, handles, mouse ? active : handles.size(), f);
      f.overlay.waiting = window::waiting_instruments(m_scene, m_state, handles);
    }
    m_frames.publish();
  }

  const Scene& m_scene;
  Simulation& m_sim;
  const SimState& m_state;  // the driver's (a session never restores: always the same)
  const Composition& m_comp;
  std::map<int, std::string> m_names;
  bool m_through_scope = false;  // the last frame published was the endoscope's view
  float m_aspect;
  TripleBuffer<render::RenderFrame>& m_frames;
  Control& m_control;
  std::optional<DrawnSurface> m_drawn;  // built on the solver thread, which draws from it
  render::Scenery m_scenery;            // the organs' surroundings, built with m_drawn
  std::uint64_t m_version = 0;          // topology the last frame showed (counts cuts)
  std::optional<render::Camera> m_fitted;
  double m_step_ms = 0.0;
  double m_rate_hz = 0.0;
  std::int64_t m_cuts = 0;
  bool m_slow = false;
  Clock::time_point m_published{};  // when the last frame was published
  std::int64_t m_steps = 0;
  bool m_hap_started = false;
  Clock::time_point m_hap_t0{};
  std::uint64_t m_hap_tick0 = 0;
  double m_hap_rate_hz = 0.0;
  std::exception_ptr m_error;
};

}  // namespace

int run_session(const std::filesystem::path& scene_path, const SessionOptions& so) {
  const double seconds = so.seconds;
  const std::filesystem::path& snapshot = so.snapshot;
  // Its outputs' places first: a trainee's session must not end on a typo.
  if (so.record) check_output_file("--record", *so.record);
  if (so.report) check_output_file("--report", *so.report);
  if (so.view_log) check_output_file("--view-log", *so.view_log);
  if (!snapshot.empty()) check_output_file("--snapshot", snapshot);
  Scene loaded = load_scene(scene_path);
  std::vector<std::optional<ToolState>> rest_pose;  // how the mouse's instruments rest
  std::vector<LivePoseStage::Source> live_poses;
  std::unique_ptr<window::ScopeControl> scope;  // the endoscope in the trainee's hands
  if (so.tool_path) {
    play_tool_path(loaded, *so.tool_path);
  } else if (auto given = give_instruments_to_trainee(loaded, haptics::rig_plugged_in())) {
    spdlog::info("the instruments follow the {} (serosa headless plays the scene's script)",
                 given->device == DeviceKind::kRig ? "rig" : "mouse and keyboard");
    rest_pose = std::move(given->start_pose);
    for (std::size_t i = 0; i < given->scope_start.size() && !scope; ++i) {
      if (!given->scope_start[i]) continue;
      scope = std::make_unique<window::ScopeControl>(loaded.tools[i], *given->scope_start[i]);
      live_poses.push_back({i, &scope->pose()});
      spdlog::info("the endoscope follows the right mouse button, I/K and ,/.");
    }
  }
  SimulationHooks hooks;
  hooks.compose = [&rest_pose, &live_poses](ComposeOptions& co) {
    co.mouse_rest_pose = rest_pose;
    co.live_poses = live_poses;
    co.realtime_haptics = true;  // the trainee's machine: SCHED_FIFO when granted
  };
  hooks.caller_paces = true;
  hooks.run_name = "session";
  HeadlessOptions driven;
  driven.steps = 0;  // open-ended: the trainee ends it
  driven.record = so.record;
  driven.progress = false;
  Simulation sim(std::move(loaded), driven, std::move(hooks));
  sim.reserve(std::int64_t{1} << 18);  // 22 min at 200 Hz before the solver thread allocates
  const Scene& scene = sim.scene();
  const Composition& comp = sim.composition();
  const SimState& state = sim.state();
  const bool mouse = comp.haptics != nullptr && comp.haptics->device_kind() == DeviceKind::kMouse;
  const bool in_hands =
      comp.haptics != nullptr && comp.haptics->device_kind() != DeviceKind::kScript;
  window::PointerControl pointer;
  std::optional<window::ViewLog> view_log;
  if (so.view_log) {
    std::vector<std::string> names;
    for (const Tool& t : scene.tools) names.push_back(t.name);
    view_log.emplace(*so.view_log, std::move(names));
  }
  // The controls show by themselves the first time a trainee (or this machine) drives.
  bool show_help =
      in_hands && !so.help_file.empty() && trainee::first_time_help(so.help_file, so.trainee);

  const window::InterruptGuard interrupts;
  render::Window window(scene.render.width, scene.render.height, "Serosa");
  render::FrameRenderer renderer;
  // Software GL's workers yield to the solver (render/renderer_threads.h).
  if (const int n = render::lower_software_renderer_threads(10); n > 0)
    spdlog::debug("session: {} software renderer threads at nice 10", n);
  render::ScaledTarget scaled;  // the pacer's lower resolutions
  render::Overlay overlay;
  render::SnapshotOptions options;
  options.tessellation = scene.render.tessellation;
  options.shape_factor = static_cast<float>(scene.render.shape_factor);
  bool show_overlay = true;
  int asked_tessellation = scene.render.tessellation;  // the scene's or the keys'
  window::FramePacer pacer(asked_tessellation, kMaxFramesPerS);
  window::FrameRate frame_rate;

  TripleBuffer<render::RenderFrame> frames;
  Control control;
  SolverLoop loop(
      sim, static_cast<float>(window.width()) / static_cast<float>(std::max(window.height(), 1)),
      frames, control);
  {
    // Before the solver starts, so that the report's wall time covers every step it paced.
    const auto start = Clock::now();
    // Declared last: stopped and joined first when the scope ends, also on an exception.
    std::jthread solver([&loop](const std::stop_token& stop) { loop.run(stop); });

    auto last = start;
    std::int64_t frames_drawn = 0;
    std::optional<double> snapshot_flat;  // the share of flat tiles in the --snapshot picture
    bool ended = false;  // by the trainee (Esc): the summary follows, until they leave it
    bool timed_out = false;
    while (!window.should_close() && !interrupts.interrupted() && !control.finished.load()) {
      std::this_thread::sleep_until(pacer.next_frame());  // the solver's core stays its own
      window.poll_events();
      if (window.pressed(render::Key::kEscape)) {
        ended = true;
        break;
      }
      if (window.pressed(render::Key::kSpace)) control.paused.store(!control.paused.load());
      if (window.pressed(render::Key::kV))
        options.view =
            static_cast<render::SnapshotOptions::View>((static_cast<int>(options.view) + 1) % 3);
      if (window.pressed(render::Key::kUp))
        asked_tessellation = std::min(asked_tessellation + 1, 16);
      if (window.pressed(render::Key::kDown))
        asked_tessellation = std::max(asked_tessellation - 1, 1);
      pacer.set_tessellation(asked_tessellation);
      options.tessellation = pacer.tessellation();
      const bool help_key = window.pressed(render::Key::kH);
      if (window.pressed(render::Key::kF1) || help_key) show_help = !show_help;
      if (window.pressed(render::Key::kF2)) show_overlay = !show_overlay;
      const window::PointerEvents events = window::pointer_events(window);
      if (mouse) {
        comp.haptics->feed_pointer(
            pointer.update(events, window::screen_axes(frames.front().camera)));
        control.active_handle.store(pointer.active());
      }
      if (scope) scope->update(window);

      frames.take();  // the newest frame, if the solver published one since
      const render::RenderFrame& frame = frames.front();
      const int w = window.width();
      const int h = window.height();
      window.bind_framebuffer();
      int draw_w = w, draw_h = h;
      if (options.lens && options.view == render::SnapshotOptions::View::kVisual) {
        // The optic's pass stretches the picture over the window itself: no second pass.
        render::scaled_size(w, h, pacer.resolution_scale(), draw_w, draw_h);
        renderer.draw(frame, options, draw_w, draw_h);
      } else {
        scaled.begin(w, h, pacer.resolution_scale(), draw_w, draw_h);
        renderer.draw(frame, options, draw_w, draw_h);
        scaled.present(w, h);
      }

      const auto now = Clock::now();
      render::OverlayInput input;
      window.cursor(input.mouse_x, input.mouse_y);
      input.mouse_down = window.mouse_down();
      input.dt_s = std::chrono::duration<float>(now - last).count();
      last = now;
      render::OverlayData shown = frame.overlay;
      shown.visible = show_overlay;
      shown.help = show_help;
      shown.frame_rate_hz = frame_rate.hz();
      shown.drawn_tessellation = options.tessellation;
      shown.drawn_scale = pacer.resolution_scale();
      const render::OverlayResult r = overlay.draw(shown, options, w, h, input);
      if (r.view) options.view = *r.view;
      if (r.tessellation) asked_tessellation = *r.tessellation;
      if (view_log)
        view_log->write(frame, w, h, std::chrono::duration<double>(now - start).count(),
                        mouse ? static_cast<int>(pointer.active()) : -1);
      const bool last_frame =
          seconds > 0.0 && std::chrono::duration<double>(now - start).count() > seconds;
      if (!snapshot.empty() && (last_frame || window.should_close() || interrupts.interrupted())) {
        const render::Image picture = window.read_image();
        snapshot_flat = render::flat_block_fraction(picture);
        render::write_png(picture, snapshot);
      }
      window.swap_buffers();
      ++frames_drawn;
      pacer.frame_done(Clock::now(), frame.overlay.slow_motion && !frame.overlay.paused);
      frame_rate.tick(Clock::now());

      char title[160];
      std::snprintf(title, sizeof title, "Serosa  t=%.2f s  FEM %.2f ms/step  %s  tess %d%s%s",
                    frame.overlay.sim_time_s, frame.overlay.fem_ms_per_step,
                    render::view_name(options.view), options.tessellation,
                    frame.overlay.paused ? "  [paused]" : "",
                    frame.overlay.slow_motion ? "  [slow motion]" : "");
      window.set_title(title);
      if (last_frame) {
        timed_out = true;
        break;
      }
    }
    solver.request_stop();
    solver.join();
    const double wall = std::chrono::duration<double>(Clock::now() - start).count();
    spdlog::info("session: {} frames drawn in {:.1f} s, simulated {:.2f} s{}", frames_drawn, wall,
                 state.time_s, interrupts.interrupted() ? " (interrupted)" : "");
    // The solver has stopped: the haptic loop next (motors off), then the recording.
    nlohmann::json report;
    report["scene"] = std::filesystem::absolute(scene.file).lexically_normal().string();
    report["frames_drawn"] = frames_drawn;
    report["wall_time_s"] = wall;
    report["steps_taken"] = loop.steps();
    report["simulated_time_s"] = state.time_s;
    // Paced to the clock, so at most 1: below it the trainee saw slow motion.
    report["real_time_factor"] = wall > 0.0 ? state.time_s / wall : 0.0;
    report["step_time_ms"] = step_time_json(sim.step_ms());
    report["frames_per_s"] = wall > 0.0 ? static_cast<double>(frames_drawn) / wall : 0.0;
    report["render"] = {{"tessellation_asked", asked_tessellation},
                        {"tessellation_drawn", pacer.tessellation()},
                        {"max_fps", pacer.max_fps()},
                        {"resolution_scale", pacer.resolution_scale()},
                        {"deepest_rung", pacer.deepest_rung()},
                        {"steps_down", pacer.steps_down()},
                        {"lens", options.lens},
                        {"camera", loop.through_scope() ? "endoscope" : "fitted"}};
    if (snapshot_flat) report["render"]["snapshot_flat"] = *snapshot_flat;
    report["interrupted"] = interrupts.interrupted();
    report.update(sim.stop());  // the haptic loop (motors off), then the recording
    add_metrics_blocks(report, scene, comp.metrics, state.mesh, sim.assembled().group_names());
    report["state_hash"] = hash_hex(state_hash(state));
    if (comp.cutting) report["cutting"] = cutting_json(comp);  // as headless reports it
    if (so.report) {
      std::ofstream out(*so.report);
      out << report.dump(2) << '\n';
      if (!out)
        throw InputError(so.report->string(), 0, "cannot write the report", "a writable path");
    }
    // The assessment's summary: after a session the trainee ended (until they leave it), or one
    // that --seconds ended when --summary-seconds asks for it; never after the window was closed,
    // Ctrl-C or a solver error.
    if (report.contains("assessment") && !window.should_close() && !interrupts.interrupted() &&
        !loop.error() && (ended || (timed_out && so.summary_seconds > 0.0)))
      window::show_summary(window, renderer, frames.front(), options, overlay,
                           session_summary(report), timed_out ? so.summary_seconds : 0.0, snapshot,
                           interrupts.flag());
  }
  if (loop.error()) std::rethrow_exception(loop.error());
  return 0;
}

}  // namespace serosa::app
