// Helpers shared by the app tests: output folders and running the built `serosa` executable.
#pragma once

#include <filesystem>
#include <string>

#include "app/shell_command.h"
#include "support/test_paths.h"

namespace serosa::app::testing {

namespace fs = std::filesystem;

inline fs::path out_dir(const std::string& name) {
  const fs::path d = fs::path(::serosa::test_paths::binary_dir()) / "test-output" / "app" / name;
  fs::remove_all(d);
  fs::create_directories(d);
  return d;
}

inline fs::path source(const std::string& rel) {
  return fs::path(::serosa::test_paths::source_dir()) / rel;
}

inline fs::path serosa_exe() {
  return fs::path(::serosa::test_paths::binary_dir()) / "app" / "serosa";
}

struct CliResult {
  int code = -1;
  std::string out;  ///< stdout and stderr together
};

/// Runs `serosa ARGS` (a shell command line tail), capturing stdout and stderr; under `wrapper`
/// (a command line head, as xvfb-run's) when given.
inline CliResult run_serosa(const std::string& args, const std::string& wrapper = {}) {
  const Command c = run_command(wrapper + shell_quote(serosa_exe().string()) + " " + args);
  return {c.code, c.output};
}

/// `serosa ARGS` in a virtual display (software GL), as a trainee's window would run.
inline CliResult run_serosa_under_xvfb(const std::string& args) {
  return run_serosa(args, "xvfb-run -a -s '-screen 0 1280x720x24' ");
}

}  // namespace serosa::app::testing
