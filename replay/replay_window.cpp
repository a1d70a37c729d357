// The instructor's replay in a window (app/session.h run_replay_window): a ReplayController
// played at the wall clock's pace, drawn with the overlay's timeline, and branched into a new
// recording when the instructor takes over.
#include <spdlog/spdlog.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <fstream>
#include <optional>
#include <string>

#include "app/compose.h"
#include "app/drawn_surface.h"
#include "app/render_frame_from_surface.h"
#include "app/scenery_from_scene.h"
#include "app/session.h"
#include "app/session_summary.h"
#include "engine/scene/scene.h"
#include "metrics/metrics_stage.h"
#include "render/camera.h"
#include "render/frame_renderer.h"
#include "render/overlay.h"
#include "render/png_writer.h"
#include "render/window.h"
#include "replay/branch_assessment.h"
#include "replay/branch_banner.h"
#include "replay/mouse_takeover.h"
#include "replay/replay_controller.h"
#include "replay/replay_timeline.h"
#include "replay/replay_window.h"
#include "window/overlay_stats.h"
#include "window/pointer_control.h"
#include "window/summary_screen.h"
#include "window/window_interrupt.h"
#include "window/window_pointer.h"

namespace serosa::replay {

using namespace serosa::app;  // the driver, the composition and the window's parts
namespace {

using Clock = std::chrono::steady_clock;

void write_layout_log(const std::filesystem::path& file, int width, int height,
                      const render::OverlayResult& r, const render::OverlayData& data) {
  nlohmann::json log;
  log["window"] = {width, height};
  log["replay_bar"] = r.replay_bar;
  log["timeline"] = r.timeline;
  log["debrief"] = r.debrief;
  log["statistics"] = r.stats_rect;
  log["debrief_text"] =
      data.debrief ? render::summary_text(*data.debrief, false) : std::vector<std::string>{};
  log["errors_line"] = render::overlay_text(data).errors;
  log["marks"] = nlohmann::json::array();
  for (const render::TimelineMark& m : data.timeline.marks)
    log["marks"].push_back({{"time_s", m.time_s}, {"what", m.what}, {"criterion", m.criterion}});
  std::ofstream(file) << log.dump(1) << "\n";
}

// The replay window's state from frame to frame, and what each frame does.
class ReplayWindow {
 public:
  ReplayWindow(const std::filesystem::path& recording, const ReplayWindowOptions& ro)
      : m_recording(recording),
        m_ro(ro),
        m_replay(recording, controller_options(ro)),
        m_names(drawn_group_names(m_replay.scene(), m_replay.group_names())),
        m_drawn(m_replay.state().mesh),
        m_timeline(recording),
        m_window(m_replay.scene().render.width, m_replay.scene().render.height, "Serosa replay"),
        m_version0(m_replay.state().mesh.topology_version) {
    const Scene& scene = m_replay.scene();
    m_options.tessellation = scene.render.tessellation;
    m_options.shape_factor = static_cast<float>(scene.render.shape_factor);
    m_frame.scenery = scenery_from_scene(scene, m_replay.state().mesh);  // once: it never changes
    fill_taenia(m_replay.state().mesh, m_names, m_frame);                // nor does this
  }

  int run() {
    const auto start = Clock::now();
    m_last = start;
    while (!m_window.should_close() && !m_interrupts.interrupted()) {
      m_window.poll_events();
      keys();
      const TimelineData known = m_timeline.data();
      timeline_keys(known);
      const auto now = Clock::now();
      const double wall_dt = play(now);
      const bool last_frame =
          m_ro.seconds > 0.0 && std::chrono::duration<double>(now - start).count() > m_ro.seconds;
      const bool leaving =
          last_frame || m_end_branch_asked || m_window.should_close() || m_interrupts.interrupted();
      if (m_replay.branched()) m_branch_debrief.update(m_replay, known.marks, leaving);
      fill_frame(known);
      draw(wall_dt, leaving);
      m_window.set_title(title(known));
      if (last_frame || m_end_branch_asked) break;
    }
    finish();
    return 0;
  }

 private:
  static ReplayControllerOptions controller_options(const ReplayWindowOptions& ro) {
    ReplayControllerOptions co;
    co.snapshot_every_s = 1.0;  // seeks back restore the nearest snapshot: exact and quick
    co.speed = ro.speed;
    return co;
  }

  void keys() {
    if (m_window.pressed(render::Key::kEscape)) {
      if (m_replay.branched())
        m_end_branch_asked = true;  // its summary first
      else
        m_window.close();
    }
    if (m_window.pressed(render::Key::kSpace)) m_replay.set_paused(!m_replay.paused());
    if (m_window.pressed(render::Key::kLeft)) m_replay.seek(m_replay.time_s() - 1.0);
    if (m_window.pressed(render::Key::kRight)) m_replay.seek(m_replay.time_s() + 1.0);
    if (m_window.pressed(render::Key::kPlus)) m_replay.set_speed(2.0 * m_replay.speed());
    if (m_window.pressed(render::Key::kMinus)) m_replay.set_speed(0.5 * m_replay.speed());
    if (m_window.pressed(render::Key::kV))
      m_options.view =
          static_cast<render::SnapshotOptions::View>((static_cast<int>(m_options.view) + 1) % 3);
    if (m_window.pressed(render::Key::kUp))
      m_options.tessellation = std::min(m_options.tessellation + 1, 16);
    if (m_window.pressed(render::Key::kDown))
      m_options.tessellation = std::max(m_options.tessellation - 1, 1);
    if (m_window.pressed(render::Key::kH)) m_show_overlay = !m_show_overlay;
    if (m_window.pressed(render::Key::kB) && !m_replay.branched()) branch_here();
    const window::PointerEvents events =
        window::pointer_events(m_window);  // taken every frame: none pile up
    if (m_takeover) {
      if (window::ScopeControl* scope_control = m_takeover->scope())
        scope_control->update(m_window);
      m_takeover->apply(m_pointer.update(events, window::screen_axes(m_frame.camera)), m_replay);
    }
  }

  // N and P jump between the errors (not in a branch: it plays on, no seeking; P is its pedal).
  void timeline_keys(const TimelineData& known) {
    if (m_window.pressed(render::Key::kN) && !m_replay.branched())
      jump_to(mark_to_jump_to(known.marks, m_current_mark, m_replay.time_s()), known.marks);
    if (m_window.pressed(render::Key::kP) && !m_replay.branched())
      jump_to(mark_to_jump_back_to(known.marks, m_replay.time_s()), known.marks);
    if (!m_debrief && known.done && known.report.contains("assessment"))
      m_debrief = session_summary(known.report, &known.failures);
  }

  // A second before the mark, so that the instructor sees what led up to it.
  void jump_to(std::optional<std::size_t> k, const std::vector<render::TimelineMark>& marks) {
    if (!k) return;
    m_current_mark = static_cast<int>(*k);
    m_replay.seek(std::max(marks[*k].time_s - kJumpLeadS, 0.0));
  }

  // Takes the steps that became due over the wall time since the last frame (at most 0.1 s of it,
  // so that a slow step plays in slow motion rather than in a catch-up burst); that wall time, s.
  double play(Clock::time_point now) {
    const double wall_dt = std::chrono::duration<double>(now - m_last).count();
    m_last = now;
    const auto t0 = Clock::now();
    const std::uint64_t taken = m_replay.advance(std::min(wall_dt, 0.1));
    if (taken > 0)
      m_step_ms = std::chrono::duration<double, std::milli>(Clock::now() - t0).count() /
                  static_cast<double>(taken);
    if (wall_dt > 0.0) m_rate_hz = 0.9 * m_rate_hz + 0.1 * static_cast<double>(taken) / wall_dt;
    if (m_replay.at_end()) m_replay.set_paused(true);
    if (m_ro.branch_at_s && !m_replay.branched() && m_replay.time_s() >= *m_ro.branch_at_s) {
      branch_here();
      m_replay.set_paused(false);  // scripted checks: the branch records at rest input
    }
    return wall_dt;
  }

  void branch_here() {
    m_replay.set_paused(true);
    std::filesystem::path file = m_ro.branch_file.value_or(std::filesystem::path{});
    if (file.empty()) {
      file = m_recording;
      std::string name = m_recording.stem().string();
      name.append(".branch-").append(std::to_string(m_replay.steps_taken())).append(".lapr");
      file.replace_filename(name);
    }
    m_replay.branch(file);
    m_branch_path = file;
    m_takeover.emplace(m_replay.scene(), m_replay.state().tools);
    m_pointer = window::PointerControl(m_takeover->initial_input());
    spdlog::info(
        "replay: branched at {:.3f} s (step {}) into {}; the mouse takes over (Tab: other "
        "hand, X: next instrument)",
        m_replay.time_s(), m_replay.steps_taken(), file.string());
  }

  void fill_frame(const TimelineData& known) {
    const Scene& scene = m_replay.scene();
    const SimState& state = m_replay.state();
    fill_render_frame(state.mesh, m_drawn.of(state), m_names, true, m_frame,
                      &state.blocks.cutting.coagulated, state.blocks.cutting.coagulated_version,
                      &state.blocks.bleeding.stain);
    fill_render_tools(scene, state, m_frame);
    std::optional<render::Camera> cam = endoscope_view(scene, state);
    if (!cam) {
      if (!m_fitted)
        m_fitted =
            render::auto_camera(m_frame, static_cast<float>(m_window.width()) /
                                             static_cast<float>(std::max(m_window.height(), 1)));
      cam = m_fitted;
    }
    m_frame.camera = *cam;
    m_frame.overlay =
        window::overlay_data(frame_stats());  // the metrics are the debrief's, by domain
    if (m_takeover)
      m_frame.overlay.branch =
          branch_banner(scene, *m_takeover,
                        {*m_replay.branch_step(), m_replay.dt_s(), m_pointer.active(),
                         m_replay.steps_taken() < m_replay.num_steps()});
    m_frame.overlay.visible = m_show_overlay;
    m_frame.overlay.timeline = {known.force_n, known.marks,
                                static_cast<double>(known.computed) * m_replay.dt_s(), known.done,
                                m_current_mark};
    m_frame.overlay.debrief = m_debrief;
    if (m_replay.branched()) {  // its own errors and assessment
      m_frame.overlay.timeline.marks = m_branch_debrief.marks();
      m_frame.overlay.debrief = m_branch_debrief.summary();
    }
  }

  [[nodiscard]] window::FrameStats frame_stats() const {
    const SimState& state = m_replay.state();
    window::FrameStats stats;
    stats.sim_time_s = state.time_s;
    stats.fem_ms_per_step = m_step_ms;
    stats.solver_rate_hz = m_rate_hz;
    // Every cut bumps the topology version, which snapshots keep: cuts survive seeks.
    stats.cuts = static_cast<std::int64_t>(state.mesh.topology_version - m_version0);
    stats.paused = m_replay.paused();
    stats.replay = true;
    stats.replay_position_s = m_replay.time_s();
    stats.replay_duration_s = m_replay.duration_s();
    stats.replay_speed = m_replay.speed();
    return stats;
  }

  void draw(double wall_dt, bool leaving) {
    const int w = m_window.width();
    const int h = m_window.height();
    m_window.bind_framebuffer();
    m_renderer.draw(m_frame, m_options, w, h);
    render::OverlayInput input;
    m_window.cursor(input.mouse_x, input.mouse_y);
    input.mouse_down = m_window.mouse_down();
    input.dt_s = static_cast<float>(std::max(wall_dt, 1e-3));
    const render::OverlayResult r = m_overlay.draw(m_frame.overlay, m_options, w, h, input);
    if (r.view) m_options.view = *r.view;
    if (r.tessellation) m_options.tessellation = *r.tessellation;
    if (r.toggle_pause) m_replay.set_paused(!m_replay.paused());
    if (r.seek_s) m_replay.seek(*r.seek_s);
    if (!m_ro.snapshot.empty() && leaving) render::write_png(m_window.read_image(), m_ro.snapshot);
    if (!m_ro.layout_log.empty() && leaving)
      write_layout_log(m_ro.layout_log, w, h, r, m_frame.overlay);
    m_window.swap_buffers();
  }

  // "Serosa replay  2.53 / 5.00 s  x1  [paused]  visual  errors 3  error 1/3": what scripts read.
  [[nodiscard]] std::string title(const TimelineData& known) const {
    const std::size_t n = m_frame.overlay.timeline.marks.size();
    char errors[64] = "";
    if (known.done && m_current_mark >= 0)
      std::snprintf(errors, sizeof errors, "  errors %zu  error %d/%zu", n, m_current_mark + 1, n);
    else if (known.done)
      std::snprintf(errors, sizeof errors, "  errors %zu", n);
    char title[224];
    std::snprintf(title, sizeof title, "Serosa replay  %.2f / %.2f s  x%.3g%s  %s%s",
                  m_replay.time_s(), m_replay.duration_s(), m_replay.speed(),
                  m_replay.paused() ? "  [paused]" : "", render::view_name(m_options.view), errors);
    return title;
  }

  // A branch ends with its report, and with its summary when the instructor ended it (Esc).
  void finish() {
    if (!m_replay.branched()) {
      spdlog::info("replay: {} of {} steps shown", m_replay.steps_taken(), m_replay.num_steps());
      return;
    }
    const nlohmann::json report = finish_branch(m_replay, m_branch_path);
    if (m_end_branch_asked && !m_interrupts.interrupted() && report.contains("assessment"))
      window::show_summary(m_window, m_renderer, m_frame, m_options, m_overlay,
                           session_summary(report), 0.0, {}, m_interrupts.flag());
  }

  std::filesystem::path m_recording;
  const ReplayWindowOptions& m_ro;
  ReplayController m_replay;
  std::map<int, std::string> m_names;
  DrawnSurface m_drawn;
  // The timeline, computed beside the replay (replay/replay_timeline.h).
  const TimelineBuilder m_timeline;
  std::optional<render::SessionSummary> m_debrief;  // once the timeline has assessed the run
  int m_current_mark = -1;                          // the mark last jumped to
  // The branch: the mouse's takeover, its file, its own marks and assessment.
  std::optional<MouseTakeover> m_takeover;
  window::PointerControl m_pointer;
  std::filesystem::path m_branch_path;
  BranchDebrief m_branch_debrief;
  bool m_end_branch_asked = false;
  const window::InterruptGuard m_interrupts;
  render::Window m_window;
  render::FrameRenderer m_renderer;
  render::Overlay m_overlay;
  render::SnapshotOptions m_options;
  bool m_show_overlay = true;
  render::RenderFrame m_frame;
  std::optional<render::Camera> m_fitted;
  std::uint64_t m_version0;
  double m_step_ms = 0.0;  // wall time of a step, ms
  double m_rate_hz = 0.0;  // steps per wall second
  Clock::time_point m_last;
};

}  // namespace

int run_replay_window(const std::filesystem::path& recording, const ReplayWindowOptions& ro) {
  ReplayWindow window(recording, ro);
  return window.run();
}

}  // namespace serosa::replay
