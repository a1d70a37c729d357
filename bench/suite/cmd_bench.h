// The `serosa bench` command (the accuracy-versus-time suite, bench/suite/): registered by the
// command line's main beside app/'s own commands (app/command.h).
#pragma once

#include <CLI/CLI.hpp>

#include "app/command.h"

namespace serosa::bench {

/// Adds `bench` and its flags to `app`; sets `action` to run the chosen parts.
void add_bench_command(CLI::App& app, app::Action& action);

}  // namespace serosa::bench
