// --camera endoscope|fitted on `serosa headless` and `serosa replay`: which camera their
// pictures (--frames) are taken from.
#pragma once

#include <CLI/CLI.hpp>

namespace serosa::app {

/// Adds --camera to `cmd`: "endoscope" (the default: what the trainee saw, while a device poses
/// the scene's endoscope) sets `fitted` false, "fitted" (one camera fitted to the organs) true.
void add_camera_option(CLI::App& cmd, bool& fitted);

}  // namespace serosa::app
