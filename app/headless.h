// A headless run of a scene: no window, no device; the solver pipeline as fast as it goes, with
// a report, the final mesh and pictures on request (docs/headless-report.md).
#pragma once

#include <atomic>
#include <cstdint>
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "engine/recording_format.h"
#include "engine/recording_writer.h"
#include "engine/scene.h"
#include "engine/scene_override.h"

namespace serosa::app {

struct Composition;

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

/// The header of a recording of `scene` (engine/recording_format.h lists the keys).
[[nodiscard]] recording::Header recording_header(const Scene& scene, std::int64_t steps);

/// Closes the run's recording after `steps` steps and returns the report's "recording" object:
/// file, steps, chunks, bytes, hash_every, snapshots.
[[nodiscard]] nlohmann::json close_recording(recording::RecordingWriter& writer, const Scene& scene,
                                             std::uint64_t steps);

/// A state hash as the report writes it: 16 lower-case hex digits.
[[nodiscard]] std::string hash_hex(std::uint64_t hash);

/// Where one step's time went: the FEM stage's share and what its solve did.
struct StepDetail {
  double fem_ms = 0.0;          ///< wall time of the FEM stage, ms
  int cg_iterations = 0;        ///< CG iterations of its solve
  bool factor_refresh = false;  ///< a factor refresh was asked for (or computed) on this step
  bool factor_patch = false;    ///< changed rows got a factor of their own on this step
};

/// The report's "step_time_ms" object: p50, p99 and max of the solver steps' wall times (ms),
/// and the eight slowest steps (`slowest`: step index from 0, ms), slowest first. With
/// `details` (one per step), each slowest step also says its FEM time, CG iterations and
/// factor work.
[[nodiscard]] nlohmann::json step_time_json(const std::vector<double>& ms,
                                            const std::vector<StepDetail>& details = {});

/// The report's "cutting" object (empty without a cutting stage).
[[nodiscard]] nlohmann::json cutting_json(const Composition& comp);

/// Runs the scene and returns the report (also written to options.report when set). Throws
/// InputError on bad input (scene, meshes, tool paths).
nlohmann::json run_headless(const HeadlessOptions& options);

}  // namespace serosa::app
