// A headless run of a scene: no window, no device; the solver pipeline as fast as it goes, with
// a report, the final mesh and pictures on request (shared/DESIGN.md, `serosa headless`).
#pragma once

#include <cstdint>
#include <filesystem>
#include <optional>

#include <nlohmann/json.hpp>

namespace serosa::app {

struct HeadlessOptions {
  std::filesystem::path scene;                        ///< scene TOML
  std::optional<std::int64_t> steps;                  ///< default: the scene's headless.steps
  std::optional<std::filesystem::path> tool_path;     ///< replaces every scripted tool's CSV
  std::optional<std::filesystem::path> export_final;  ///< Gmsh 2.2 of the final state
  std::optional<std::filesystem::path> report;        ///< JSON report
  std::optional<std::filesystem::path> frames;        ///< folder for PNG pictures
  int frame_count = 5;   ///< pictures spread over the run (first and last included), with --frames
  bool progress = true;  ///< progress bar on stderr when it is a terminal
};

/// Runs the scene and returns the report (also written to options.report when set). Throws
/// InputError on bad input (scene, meshes, tool paths).
nlohmann::json run_headless(const HeadlessOptions& options);

}  // namespace serosa::app
