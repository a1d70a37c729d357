// The trainee session (`serosa run`): the scene in a window, simulated in real time.
#pragma once

#include <filesystem>
#include <optional>
#include <string>

namespace serosa::app {

/// What `serosa run` may add to the window.
struct SessionOptions {
  double seconds = 0.0;            ///< close after this much wall time when > 0 (checks)
  std::filesystem::path snapshot;  ///< when not empty: the last picture drawn, PNG
  /// .lapr recording of the session (what the solver consumed); default: the scene's [record]
  /// path, else none. `serosa replay FILE --headless --verify` re-simulates it.
  std::optional<std::filesystem::path> record;
  /// JSON report written at the end: frames, steps, simulated time, the haptic loop's telemetry
  /// ("haptics", as headless writes it), the recording, the metrics.
  std::optional<std::filesystem::path> report;
  /// A tool path every scripted tool plays instead of its own; without one the scripted
  /// instruments follow the rig when it is plugged in, else the mouse (app/instrument_devices.h).
  std::optional<std::filesystem::path> tool_path;
  /// When the scene scores the session: how long the summary screen stays after a session that
  /// `seconds` ended, s (0: not shown then). A session the trainee ends (Esc, or the procedure
  /// finished) shows it until they leave it.
  double summary_seconds = 0.0;
  /// Who drives (--trainee; empty: no name) and the file remembering who has seen the controls
  /// (trainee/help_seen.h; empty: the controls panel never shows by itself).
  std::string trainee;
  std::filesystem::path help_file;
  /// Where each frame's instruments, guide and organs were drawn, as JSON lines
  /// (window/view_log.h); none when empty.
  std::optional<std::filesystem::path> view_log;
};

/// Opens a window on the scene and runs it in real time until the window closes, Ctrl-C (SIGINT
/// or SIGTERM) arrives, or `seconds` of wall time passed (when > 0). Returns the exit code.
///
/// Threads (docs/ARCHITECTURE.md "Threads and hand-offs"): the solver runs on its own thread at the
/// scene's fixed dt, paced to real time (when a step takes longer than dt it runs in slow motion
/// and says so), and after every step publishes a RenderFrame (surface, tet edges, tools,
/// endoscope camera, overlay data) through a TripleBuffer; it never waits for drawing. When the
/// scene lists "haptics", the 1 kHz haptic loop runs on a third thread (haptics/haptics_stage.h,
/// SCHED_FIFO when granted): tool states to the solver and contact models back through seqlocks;
/// the mouse device takes the window's pointer input; the overlay shows the loop's live rate
/// (LoopStatus ticks per wall second). The calling (main) thread owns the window and its GL
/// context (GLFW requires the main thread): it takes the newest frame whenever it draws.
/// Shutdown (close, Ctrl-C, `seconds`, a solver error): the solver thread stops and joins, then
/// the haptic loop (motors off), then the recording is closed and the report written.
///
/// Keys: Space pause, V cycle the views (visual, collision, mechanical), Up/Down tessellation
/// level, O toggle a 0/30 degree scope, H or F1 the controls panel (shown by itself the first
/// time a trainee drives), F2 hide/show the overlay, Esc end the session (then the summary of
/// its assessment, when the scene scores it; Esc again to leave). With mouse-driven instruments
/// (window/pointer_control.h): drag with the left button to move the active one's tip the way the
/// pointer goes in the picture (it pivots about its trocar), W/S into and out of the picture,
/// the wheel in and out along the shaft, Q/E roll, J taps open/close the jaws and held closes them
/// steadily, P the pedal, Home back into view, Tab the other hand. The overlay names what each hand
/// holds, its jaws, pedal and distance to tissue; the active instrument wears a coloured collar and
/// a ring on the tissue under each tip closes in as it comes near. The overlay's view and
/// tessellation controls work with the mouse.
int run_session(const std::filesystem::path& scene, const SessionOptions& options);

}  // namespace serosa::app
