// Helpers shared by the app tests: output folders and running the built `serosa` executable.
#pragma once

#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <utility>
#include <vector>

#include "app/shell_command.h"
#include "engine/input_error.h"
#include "engine/scene.h"
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

/// A file's whole text ("" when it cannot be read).
inline std::string file_text(const fs::path& p) {
  std::ostringstream s;
  s << std::ifstream(p).rdbuf();
  return s.str();
}

/// Every shipped scene (config/*.toml that loads as one; the manifests and the curriculum do
/// not), with its file name.
inline std::vector<std::pair<std::string, Scene>> shipped_scenes() {
  std::vector<std::pair<std::string, Scene>> out;
  for (const auto& entry : fs::directory_iterator(source("config"))) {
    if (entry.path().extension() != ".toml") continue;
    try {
      out.emplace_back(entry.path().filename().string(), load_scene(entry.path()));
    } catch (const InputError&) {
    }
  }
  return out;
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
