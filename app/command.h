// Each serosa subcommand lives in its own file (cmd_*.cpp) and registers itself through one of
// these functions, called from main.cpp. A command returns the process exit code.
#pragma once

#include <CLI/CLI.hpp>
#include <functional>

namespace serosa::app {

/// The action a subcommand runs after CLI11 parsed its flags into captured variables.
using Action = std::function<int()>;

/// add_*_command(app, action): adds the subcommand and its flags to `app` and sets `action` to
/// what runs when the subcommand is chosen.
void add_check_command(CLI::App& app, Action& action);
void add_surface_command(CLI::App& app, Action& action);
void add_headless_command(CLI::App& app, Action& action);
void add_run_command(CLI::App& app, Action& action);
void add_cut_command(CLI::App& app, Action& action);
void add_trainee_command(CLI::App& app, Action& action);
void add_cohort_command(CLI::App& app, Action& action);
void add_tasks_command(CLI::App& app, Action& action);
void add_batch_command(CLI::App& app, Action& action);

}  // namespace serosa::app
