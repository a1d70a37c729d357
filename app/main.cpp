// serosa: the command line (docs/ARCHITECTURE.md "External contracts").
#include <spdlog/sinks/stdout_color_sinks.h>
#include <spdlog/spdlog.h>

#include <CLI/CLI.hpp>
#include <cstdio>
#include <exception>

#include "app/command.h"
#include "app/heap_policy.h"
#include "bench/suite/cmd_bench.h"
#include "engine/input_error.h"
#include "replay/cmd_replay.h"

int main(int argc, char** argv) {
  serosa::app::keep_freed_memory();
  // The log goes to stderr: stdout carries only what the command prints (a script reads
  // `headless --json` or `check --json` from it whole).
  spdlog::set_default_logger(std::make_shared<spdlog::logger>(
      "", std::make_shared<spdlog::sinks::stderr_color_sink_mt>()));
  CLI::App cli{"Serosa: real-time laparoscopic surgery simulator"};
  cli.require_subcommand(1);
  serosa::app::Action action;
  serosa::app::add_check_command(cli, action);
  serosa::app::add_surface_command(cli, action);
  serosa::app::add_headless_command(cli, action);
  serosa::app::add_run_command(cli, action);
  serosa::replay::add_replay_command(cli, action);
  serosa::app::add_cut_command(cli, action);
  serosa::bench::add_bench_command(cli, action);
  serosa::app::add_trainee_command(cli, action);
  serosa::app::add_cohort_command(cli, action);
  serosa::app::add_tasks_command(cli, action);
  serosa::app::add_batch_command(cli, action);
  try {
    cli.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    // --help and --version exit 0; a missing or unknown argument is bad input: exit 1, as every
    // other input error (CLI11's own codes, 100 and up, are not part of our contract).
    return cli.exit(e) == 0 ? 0 : 1;
  }
  // Bad input is the user's to fix: say what and where, exit 1. Anything else is our bug: exit 2.
  try {
    return action ? action() : 2;
  } catch (const serosa::InputError& e) {
    std::fprintf(stderr, "error: %s\n", e.what());
    return 1;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "internal error: %s\n", e.what());
    return 2;
  }
}
