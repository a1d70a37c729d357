// What a run of a scene without window or device is asked for (app/simulation.h runs it;
// `serosa headless` and the Python module fill it).
#pragma once

#include <atomic>
#include <cstdint>
#include <filesystem>
#include <optional>
#include <vector>

#include "engine/scene/scene_override.h"

namespace serosa::app {

struct HeadlessOptions {
  std::filesystem::path scene;           ///< scene TOML
  std::vector<SceneOverride> overrides;  ///< scene keys set over the file's
  std::optional<std::int64_t> steps;     ///< default: the scene's headless.steps
  std::optional<double> seconds;  ///< simulated time instead of steps (rounded to whole steps), s
  std::optional<std::filesystem::path> tool_path;  ///< replaces every scripted tool's CSV
  /// The final state: .msh (Gmsh 2.2), .vtu (ParaView) or .obj (its boundary surface)
  std::optional<std::filesystem::path> export_final;
  std::optional<std::filesystem::path> series;      ///< per-step CSV (app/run_series.h)
  std::optional<std::filesystem::path> vtu_series;  ///< folder of VTU files and series.pvd
  std::int64_t vtu_every = 10;                      ///< a VTU file every this many steps
  std::optional<std::filesystem::path> report;      ///< JSON report
  std::optional<std::filesystem::path> frames;      ///< folder for PNG pictures
  int frame_count = 5;  ///< pictures spread over the run (first and last included), with --frames
  /// The pictures' camera: the scene's endoscope (while a device poses it), else one fitted to
  /// the organs; true: always the fitted one.
  bool fitted_camera = false;
  bool progress = true;                         ///< progress bar on stderr when it is a terminal
  std::optional<std::filesystem::path> record;  ///< .lapr recording of the run
  /// Without `record`, record to the scene's [record] path when it gives one (a Python program
  /// records only when it asks).
  bool scene_record = true;
  bool validate_cuts = false;  ///< check every cut's invariants (cutting/validate.h); costly
  /// The final node positions in the report ("nodes_final_m"), for a golden comparison.
  bool positions = false;
  /// Set (from a signal handler, another thread) to stop after the current step; the run then
  /// ends cleanly: recording closed, report written with "interrupted": true.
  const std::atomic<bool>* stop = nullptr;
};

/// The header of a recording of `scene` (recording/recording_format.h lists the keys).
}  // namespace serosa::app
