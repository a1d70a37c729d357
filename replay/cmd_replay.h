// The `serosa replay` command (replay/): registered by the command line's main beside app/'s own
// commands (app/command.h).
#pragma once

#include <CLI/CLI.hpp>

#include "app/command.h"

namespace serosa::replay {

/// Adds `replay` and its flags to `app`; sets `action` to replay the recording, headless or in
/// a window.
void add_replay_command(CLI::App& app, app::Action& action);

}  // namespace serosa::replay
