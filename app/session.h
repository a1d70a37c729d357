// The trainee session (`serosa run`): the scene in a window, simulated in real time.
#pragma once

#include <filesystem>

namespace serosa::app {

/// Opens a window on the scene and runs it in real time until the window closes, Ctrl-C (SIGINT
/// or SIGTERM) arrives, or `seconds` of wall time passed (when > 0). Returns the exit code.
///
/// Threads: the solver runs on its own thread at the scene's fixed dt, paced to real time (when
/// a step takes longer than dt it runs in slow motion and says so), and after every step
/// publishes a RenderFrame (surface, tet edges, tools, endoscope camera, overlay data) through a
/// TripleBuffer; it never waits for drawing. The calling (main) thread owns the window and its
/// GL context (GLFW requires the main thread): it takes the newest frame whenever it draws,
/// uploading positions every frame and indices only when the topology version changed.
///
/// Keys: Space pause, V cycle the views (visual, collision, mechanical), Up/Down tessellation
/// level, O toggle a 0/30 degree scope, H hide/show the overlay, Esc quit. The overlay's view
/// and tessellation controls work with the mouse. Scripted tools follow their paths; rig and
/// mouse input join with the haptics issue.
/// When `snapshot` is not empty, the last picture drawn is also written there as a PNG.
int run_session(const std::filesystem::path& scene, double seconds,
                const std::filesystem::path& snapshot = {});

/// The instructor's replay of a .lapr recording in a window (`serosa replay REC.lapr`), driven
/// by a ReplayController (app/replay_controller.h) in snapshot-seek mode (a snapshot every
/// second): it plays at `speed` x real time, drawing the replayed scene with its wound, tools,
/// the overlay's timeline (position / length, speed, pause) and the metrics.
///
/// Keys: Space pause/play, Left/Right seek -/+ 1 s, Plus/Minus double/halve the speed, V views,
/// Up/Down tessellation, H overlay, Esc quit; the overlay's Play/Pause button and timeline work
/// with the mouse. At the end of the recording playback pauses on the last frame. Closes after
/// `seconds` of wall time when > 0 (checks), writing the last picture to `snapshot` when given.
/// Throws InputError when the file is not a usable recording.
int run_replay_window(const std::filesystem::path& recording, double speed, double seconds,
                      const std::filesystem::path& snapshot = {});

}  // namespace serosa::app
