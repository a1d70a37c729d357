// Overlay: the Dear ImGui heads-up display over the endoscope view (solver and haptic rates, cut
// count, view and tessellation, and for instructors the replay timeline), drawn with the
// project's own small OpenGL 3 renderer for ImGui's draw lists (no ImGui backend needed).
#pragma once

#include <array>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "render/render_frame.h"
#include "render/session_summary.h"
#include "render/snapshot_options.h"

struct ImGuiContext;

namespace serosa::render {

class GlProgram;

/// Pointer input for the overlay, in framebuffer pixels (origin top left).
struct OverlayInput {
  float mouse_x = -1.0f;      ///< pixels; negative: no pointer over the picture
  float mouse_y = -1.0f;      ///< pixels
  bool mouse_down = false;    ///< the primary button is held
  float dt_s = 1.0f / 60.0f;  ///< wall time since the previous overlay frame, s (> 0)
};

/// What the user asked for through the overlay this frame, and where its controls are (pixels,
/// {x0, y0, x1, y1}; zero when not shown) so that callers and tests can aim at them.
struct OverlayResult {
  bool toggle_pause = false;                  ///< the replay's pause/play button was clicked
  std::optional<double> seek_s;               ///< the timeline was dragged to this position, s
  std::optional<SnapshotOptions::View> view;  ///< another view was picked
  std::optional<int> tessellation;            ///< another tessellation level was picked
  bool wants_mouse = false;  ///< the pointer is over the overlay (do not use it for the scene)
  std::array<float, 4> stats_rect{};    ///< the statistics panel
  std::array<float, 4> pause_button{};  ///< the replay's pause/play button
  std::array<float, 4> timeline{};      ///< the replay's timeline slider
  std::array<float, 4> replay_bar{};    ///< the replay's whole panel along the bottom
  std::array<float, 4> debrief{};       ///< the replay's debrief panel (right)
};

/// Owns an ImGui context and the GL objects that draw it. Construct, use and destroy it with the
/// same OpenGL 4.1+ context current (the window's or an OffscreenContext). ImGui keeps one
/// current context per process: use one Overlay at a time (each draw makes its own current).
class Overlay {
 public:
  /// @throws std::runtime_error with the driver's log on a GLSL error
  Overlay();
  ~Overlay();
  Overlay(const Overlay&) = delete;
  Overlay& operator=(const Overlay&) = delete;
  Overlay(Overlay&&) = delete;
  Overlay& operator=(Overlay&&) = delete;

  /// Lays out and draws the overlay for `data` over the bound framebuffer (width x height
  /// pixels; the viewport must cover it). Nothing is drawn when data.visible is false.
  OverlayResult draw(const OverlayData& data, const SnapshotOptions& options, int width, int height,
                     const OverlayInput& input);
  /// Draws the end-of-session summary (render/session_summary.h) centred over the bound
  /// framebuffer (width x height pixels), in place of the statistics.
  void draw_summary(const SessionSummary& summary, int width, int height);

 private:
  OverlayResult layout(const OverlayData& data, const SnapshotOptions& options, int width,
                       int height);
  void layout_hands(const OverlayData& data, int panel, int width);
  void layout_help(int panel, int width, int height);
  void layout_replay(const OverlayData& data, int panel, int width, int height,
                     OverlayResult& result);
  void layout_debrief(const OverlayData& data, int panel, int width, float bottom,
                      OverlayResult& result);
  void render_draw_data();

  ImGuiContext* imgui_ = nullptr;
  std::unique_ptr<GlProgram> program_;
  unsigned int vao_ = 0;
  unsigned int vbo_ = 0;
  unsigned int ibo_ = 0;
  unsigned int font_tex_ = 0;
  bool first_frame_ = true;
  bool replay_shown_ = false;  // the replay panel was laid out last frame
};

/// The text the overlay shows for `data`, line by line (no GL, no ImGui: what tests check).
struct OverlayText {
  /// The statistics panel: "t = 12.50 s" (with "  [paused]", "  [slow motion]"),
  /// "FEM 3.20 ms/step  (200 steps/s)", "haptics 1000 Hz" or "haptics \u2014" (an em dash: no
  /// haptic loop runs) followed by what drives the instruments ("  (mouse)", "  (rig not
  /// connected)"), "cuts 2", then one line per metric: "max force 1.8 N".
  std::vector<std::string> stats;
  /// The replay timeline's label, "0:15.0 / 1:00.0  x1.0" (with "  [paused]"); empty outside
  /// replays.
  std::string timeline;
  /// The errors line under it: "errors 3 (N: next, P: previous)" ("no errors: every criterion
  /// passed"; "assessing the recording ..." while the timeline is being computed), then the mark
  /// last jumped to, "  2/3 0:08.0 bleeding: the artery was cut before it was secured".
  std::string errors;
  /// The instruments panel, a line per hand: "> right: scissors  jaws 1.20 of 1.20 rad  tissue
  /// 4 mm" ('>' marks the active one; "jaws closed", "pedal DOWN", "6 mm IN JAWS", "touching",
  /// "tissue far" as they are).
  std::vector<std::string> hands;
};
[[nodiscard]] OverlayText overlay_text(const OverlayData& data);

/// The controls panel (H or F1), line by line: every key and mouse action of the trainee session.
[[nodiscard]] const std::vector<std::string>& overlay_help_lines();

/// The views' names as the overlay and the window title show them: "visual", "collision",
/// "mechanical".
[[nodiscard]] const char* view_name(SnapshotOptions::View view);

}  // namespace serosa::render
