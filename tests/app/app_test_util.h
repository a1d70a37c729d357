// Helpers shared by the app tests: output folders and running the built `serosa` executable.
#pragma once

#include <sys/wait.h>

#include <array>
#include <cstdio>
#include <filesystem>
#include <string>
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
  std::string cmd = wrapper + "'";
  cmd.append(serosa_exe().string()).append("' ").append(args).append(" 2>&1");
  CliResult r;
  FILE* pipe = popen(cmd.c_str(), "r");
  if (pipe == nullptr) return r;
  std::array<char, 4096> buf{};
  std::size_t n = 0;
  while ((n = std::fread(buf.data(), 1, buf.size(), pipe)) > 0) r.out.append(buf.data(), n);
  const int status = pclose(pipe);
  r.code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  return r;
}

/// `serosa ARGS` in a virtual display (software GL), as a trainee's window would run.
inline CliResult run_serosa_under_xvfb(const std::string& args) {
  return run_serosa(args, "xvfb-run -a -s '-screen 0 1280x720x24' ");
}

}  // namespace serosa::app::testing
