// Helpers shared by the app tests: output folders and running the built `serosa` executable.
#pragma once

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <utility>
#include <vector>

#include "engine/input_error.h"
#include "engine/scene/scene.h"
#include "engine/shell_command.h"
#include "support/test_paths.h"

namespace serosa::app::testing {

namespace fs = std::filesystem;

inline fs::path out_dir(const std::string& name) {
  const fs::path d = fs::path(::serosa::test_paths::binary_dir()) / "test-output" / "app" / name;
  fs::remove_all(d);
  fs::create_directories(d);
  return d;
}

/// A folder of the running test's own, `name` followed by the test's name: CTest runs each test
/// in its own process, side by side, and a shared folder would be wiped and rewritten by one
/// test while another reads from it.
inline fs::path own_dir(const std::string& name) {
  const ::testing::TestInfo* t = ::testing::UnitTest::GetInstance()->current_test_info();
  std::string full = name;
  if (t != nullptr) full.append("_").append(t->name());
  return out_dir(full);
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
