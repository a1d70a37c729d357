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

#include "app/branch_assessment.h"
#include "app/branch_banner.h"
#include "app/compose.h"
#include "app/drawn_surface.h"
#include "app/mouse_takeover.h"
#include "app/overlay_stats.h"
#include "app/pointer_control.h"
#include "app/render_frame_from_surface.h"
#include "app/replay_controller.h"
#include "app/replay_timeline.h"
#include "app/scenery_from_scene.h"
#include "app/session.h"
#include "app/session_summary.h"
#include "app/summary_screen.h"
#include "app/window_interrupt.h"
#include "app/window_pointer.h"
#include "engine/scene.h"
#include "metrics/metrics_stage.h"
#include "render/camera.h"
#include "render/frame_renderer.h"
#include "render/overlay.h"
#include "render/png_writer.h"
#include "render/window.h"

namespace serosa::app {
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

}  // namespace

int run_replay_window(const std::filesystem::path& recording, const ReplayWindowOptions& ro) {
  const double seconds = ro.seconds;
  const std::filesystem::path& snapshot = ro.snapshot;
  ReplayControllerOptions co;
  co.snapshot_every_s = 1.0;  // seeks back restore the nearest snapshot: exact and quick
  co.speed = ro.speed;
  ReplayController replay(recording, co);
  std::optional<MouseTakeover> takeover;
  PointerControl pointer;
  std::filesystem::path branch_path;
  BranchDebrief branch_debrief;
  bool end_branch_asked = false;  // Esc in a branch: its summary, then out
  const auto branch_here = [&] {
    replay.set_paused(true);
    std::filesystem::path file = ro.branch_file.value_or(std::filesystem::path{});
    if (file.empty()) {
      file = recording;
      std::string name = recording.stem().string();
      name.append(".branch-").append(std::to_string(replay.steps_taken())).append(".lapr");
      file.replace_filename(name);
    }
    replay.branch(file);
    branch_path = file;
    takeover.emplace(replay.scene(), replay.state().tools);
    pointer = PointerControl(takeover->initial_input());
    spdlog::info(
        "replay: branched at {:.3f} s (step {}) into {}; the mouse takes over (Tab: other "
        "hand, X: next instrument)",
        replay.time_s(), replay.steps_taken(), file.string());
  };
  const Scene& scene = replay.scene();
  const std::map<int, std::string> names = drawn_group_names(scene, replay.group_names());
  DrawnSurface drawn(replay.state().mesh);
  // The metric timeline, computed beside the replay; N jumps to a second before the next error.
  const TimelineBuilder timeline(recording);
  int current_mark = -1;
  const auto jump_to_next_error = [&](const std::vector<render::TimelineMark>& marks) {
    if (replay.branched()) return;  // a branch plays on: no seeking
    const std::optional<std::size_t> k = mark_to_jump_to(marks, current_mark, replay.time_s());
    if (!k) return;
    current_mark = static_cast<int>(*k);
    replay.seek(std::max(marks[*k].time_s - kJumpLeadS, 0.0));
  };
  const auto jump_to_previous_error = [&](const std::vector<render::TimelineMark>& marks) {
    if (replay.branched()) return;
    const std::optional<std::size_t> k = mark_to_jump_back_to(marks, replay.time_s());
    if (!k) return;
    current_mark = static_cast<int>(*k);
    replay.seek(std::max(marks[*k].time_s - kJumpLeadS, 0.0));
  };
  std::optional<render::SessionSummary> debrief;  // once the timeline has assessed the run

  const InterruptGuard interrupts;
  render::Window window(scene.render.width, scene.render.height, "Serosa replay");
  render::FrameRenderer renderer;
  render::Overlay overlay;
  render::SnapshotOptions options;
  options.tessellation = scene.render.tessellation;
  options.shape_factor = static_cast<float>(scene.render.shape_factor);
  bool show_overlay = true;
  render::RenderFrame frame;
  frame.scenery = scenery_from_scene(scene, replay.state().mesh);  // once: it never changes
  fill_taenia(replay.state().mesh, names, frame);                  // nor does this
  std::optional<render::Camera> fitted;
  // Every cut bumps the topology version, which snapshots keep: cuts survive seeks.
  const std::uint64_t version0 = replay.state().mesh.topology_version;
  double step_ms = 0.0;
  double rate_hz = 0.0;

  const auto start = Clock::now();
  auto last = start;
  while (!window.should_close() && !interrupts.interrupted()) {
    window.poll_events();
    if (window.pressed(render::Key::kEscape)) {
      if (replay.branched())
        end_branch_asked = true;
      else
        window.close();
    }
    if (window.pressed(render::Key::kSpace)) replay.set_paused(!replay.paused());
    if (window.pressed(render::Key::kLeft)) replay.seek(replay.time_s() - 1.0);
    if (window.pressed(render::Key::kRight)) replay.seek(replay.time_s() + 1.0);
    if (window.pressed(render::Key::kPlus)) replay.set_speed(2.0 * replay.speed());
    if (window.pressed(render::Key::kMinus)) replay.set_speed(0.5 * replay.speed());
    if (window.pressed(render::Key::kV))
      options.view =
          static_cast<render::SnapshotOptions::View>((static_cast<int>(options.view) + 1) % 3);
    if (window.pressed(render::Key::kUp))
      options.tessellation = std::min(options.tessellation + 1, 16);
    if (window.pressed(render::Key::kDown))
      options.tessellation = std::max(options.tessellation - 1, 1);
    if (window.pressed(render::Key::kH)) show_overlay = !show_overlay;
    if (window.pressed(render::Key::kB) && !replay.branched()) branch_here();
    const PointerEvents events = pointer_events(window);  // taken every frame: none pile up
    if (takeover) {
      if (ScopeControl* scope_control = takeover->scope()) scope_control->update(window);
      takeover->apply(pointer.update(events, screen_axes(frame.camera)), replay);
    }
    const TimelineData known = timeline.data();
    if (window.pressed(render::Key::kN)) jump_to_next_error(known.marks);
    if (window.pressed(render::Key::kP) && !replay.branched()) jump_to_previous_error(known.marks);
    if (!debrief && known.done && known.report.contains("assessment"))
      debrief = session_summary(known.report, &known.failures);

    // Play: the steps that became due over the wall time since the last frame (at most 0.1 s of
    // it, so that a slow step plays in slow motion rather than in a catch-up burst).
    const auto now = Clock::now();
    const double wall_dt = std::chrono::duration<double>(now - last).count();
    last = now;
    const auto t0 = Clock::now();
    const std::uint64_t taken = replay.advance(std::min(wall_dt, 0.1));
    if (taken > 0)
      step_ms = std::chrono::duration<double, std::milli>(Clock::now() - t0).count() /
                static_cast<double>(taken);
    if (wall_dt > 0.0) rate_hz = 0.9 * rate_hz + 0.1 * static_cast<double>(taken) / wall_dt;
    if (replay.at_end()) replay.set_paused(true);
    if (ro.branch_at_s && !replay.branched() && replay.time_s() >= *ro.branch_at_s) {
      branch_here();
      replay.set_paused(false);  // scripted checks: the branch records at rest input
    }

    const bool last_frame =
        seconds > 0.0 && std::chrono::duration<double>(now - start).count() > seconds;
    const bool leaving =
        last_frame || end_branch_asked || window.should_close() || interrupts.interrupted();
    if (replay.branched()) branch_debrief.update(replay, known.marks, leaving);

    const SimState& state = replay.state();
    fill_render_frame(state.mesh, drawn.of(state), names, true, frame, &state.handoff.coagulated,
                      state.handoff.coagulated_version, &state.handoff.stain);
    fill_render_tools(scene, state, frame);
    const int w = window.width();
    const int h = window.height();
    std::optional<render::Camera> cam = endoscope_view(scene, state);
    if (!cam) {
      if (!fitted)
        fitted =
            render::auto_camera(frame, static_cast<float>(w) / static_cast<float>(std::max(h, 1)));
      cam = fitted;
    }
    frame.camera = *cam;

    FrameStats stats;
    stats.sim_time_s = state.time_s;
    stats.fem_ms_per_step = step_ms;
    stats.solver_rate_hz = rate_hz;
    stats.cuts = static_cast<std::int64_t>(state.mesh.topology_version - version0);
    stats.paused = replay.paused();
    stats.replay = true;
    stats.replay_position_s = replay.time_s();
    stats.replay_duration_s = replay.duration_s();
    stats.replay_speed = replay.speed();
    frame.overlay = overlay_data(stats);  // the metrics are the debrief's, by domain
    if (takeover)
      frame.overlay.branch = branch_banner(scene, *takeover,
                                           {*replay.branch_step(), replay.dt_s(), pointer.active(),
                                            replay.steps_taken() < replay.num_steps()});
    frame.overlay.visible = show_overlay;
    frame.overlay.timeline = {known.force_n, known.marks,
                              static_cast<double>(known.computed) * replay.dt_s(), known.done,
                              current_mark};
    frame.overlay.debrief = debrief;
    if (replay.branched()) {
      frame.overlay.timeline.marks = branch_debrief.marks();
      frame.overlay.debrief = branch_debrief.summary();
    }

    window.bind_framebuffer();
    renderer.draw(frame, options, w, h);
    render::OverlayInput input;
    window.cursor(input.mouse_x, input.mouse_y);
    input.mouse_down = window.mouse_down();
    input.dt_s = static_cast<float>(std::max(wall_dt, 1e-3));
    const render::OverlayResult r = overlay.draw(frame.overlay, options, w, h, input);
    if (r.view) options.view = *r.view;
    if (r.tessellation) options.tessellation = *r.tessellation;
    if (r.toggle_pause) replay.set_paused(!replay.paused());
    if (r.seek_s) replay.seek(*r.seek_s);
    if (!snapshot.empty() && leaving) render::write_png(window.read_image(), snapshot);
    if (!ro.layout_log.empty() && leaving) write_layout_log(ro.layout_log, w, h, r, frame.overlay);
    window.swap_buffers();

    // The errors' count once the timeline is known, and the one last jumped to.
    char errors[64] = "";
    if (known.done && current_mark >= 0)
      std::snprintf(errors, sizeof errors, "  errors %zu  error %d/%zu",
                    frame.overlay.timeline.marks.size(), current_mark + 1,
                    frame.overlay.timeline.marks.size());
    else if (known.done)
      std::snprintf(errors, sizeof errors, "  errors %zu", frame.overlay.timeline.marks.size());
    char title[224];
    std::snprintf(title, sizeof title, "Serosa replay  %.2f / %.2f s  x%.3g%s  %s%s",
                  replay.time_s(), replay.duration_s(), replay.speed(),
                  replay.paused() ? "  [paused]" : "", render::view_name(options.view), errors);
    window.set_title(title);
    if (last_frame || end_branch_asked) break;
  }
  if (replay.branched()) {
    const nlohmann::json report = finish_branch(replay, branch_path);
    if (end_branch_asked && !interrupts.interrupted() && report.contains("assessment"))
      show_summary(window, renderer, frame, options, overlay, session_summary(report), 0.0, {},
                   interrupts.flag());
  } else {
    spdlog::info("replay: {} of {} steps shown", replay.steps_taken(), replay.num_steps());
  }
  return 0;
}

}  // namespace serosa::app
