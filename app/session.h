// The trainee session (`serosa run`): the scene in a window, simulated in real time.
#pragma once

#include <filesystem>

namespace serosa::app {

/// Opens a window on the scene and runs it in real time until the window closes (or after
/// `seconds` of wall time when > 0). Keys: Space pause, V cycle the views (visual, collision,
/// mechanical), Up/Down tessellation level, Esc quit. Scripted tools follow their paths; rig and
/// mouse input join with the haptics issue. Returns the exit code.
/// This first session runs solver and drawing on one thread, stepping as many solver steps per
/// frame as wall time asks (at most 8, then it runs slow-motion and says so in the title).
int run_session(const std::filesystem::path& scene, double seconds);

}  // namespace serosa::app
