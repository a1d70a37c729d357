// The instructor's replay in a window (`serosa replay REC.lapr` without --headless).
#pragma once

#include <filesystem>
#include <optional>

namespace serosa::replay {

/// The instructor's replay of a .lapr recording in a window (`serosa replay REC.lapr`), driven
/// by a ReplayController (replay/replay_controller.h) in snapshot-seek mode (a snapshot every
/// second): it plays at `speed` x real time, drawing the replayed scene with its wound, tools,
/// the overlay's timeline (position / length, speed, pause) and the metrics.
///
/// Beside the picture: the debrief (app/session_summary.h: verdict, score, domains, what failed
/// in words, steps, metrics by domain) once the timeline (replay/replay_timeline.h) has assessed
/// the recording, whose failed criteria it marks.
///
/// Keys: Space pause/play, Left/Right seek -/+ 1 s, N/P the next/previous error, Plus/Minus
/// double/halve the speed, V views, Up/Down tessellation, H the panels (never the timeline), Esc
/// quit; the overlay's Play/Pause button and timeline work
/// with the mouse. At the end of the recording playback pauses on the last frame. Closes after
/// `seconds` of wall time when > 0 (checks), writing the last picture to `snapshot` when given.
///
/// Branch (B, or automatically at `branch_at_s` when given): pauses and branches from the replayed
/// state (bit for bit the recorded one, seeks included) into `branch_file`
/// (default: next to the recording, NAME.branch-STEP.lapr); from then on the mouse drives the
/// instruments (replay/mouse_takeover.h; the session's keys: drag, W/S, Q/E, J, Tab) and Space
/// resumes. The branch recording is closed when the window closes.
/// Throws InputError when the file is not a usable recording.
struct ReplayWindowOptions {
  double speed = 1.0;
  double seconds = 0.0;
  std::filesystem::path snapshot;
  std::optional<double> branch_at_s;  ///< branch automatically at this time, s
  std::optional<std::filesystem::path> branch_file;
  /// Written with the last picture (checks): the window's size, where the overlay's panels were
  /// ({x0, y0, x1, y1} pixels) and what the debrief said, as JSON; empty: not written.
  std::filesystem::path layout_log;
};
int run_replay_window(const std::filesystem::path& recording, const ReplayWindowOptions& options);

}  // namespace serosa::replay
