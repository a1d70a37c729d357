// Per-step outputs of a headless run for an engineer's own tools: a CSV time series (one row a
// step: time, wall time, the solve's iterations and residual, the tissue's mechanical energy,
// each tool's force on the tissue) and a VTU series for ParaView (the mesh every N steps and a
// .pvd collection naming each file's simulated time).
#pragma once

#include <cstdint>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include "engine/scene/scene.h"
#include "engine/sim_state.h"
#include "fem/implicit_integrator.h"

namespace serosa::app {

/// `--series F.csv`: time_s, step, step_ms, fem_ms, cg_iterations, residual, energy_j, then
/// force_n.TOOL (N, the norm of the tool's force on the tissue) for each of the scene's tools.
class StepSeries {
 public:
  StepSeries(const std::filesystem::path& file, const Scene& scene);
  /// One row, after the step: `status` is the FEM stage's (zeros without FEM).
  void add(const SimState& state, double step_ms, double fem_ms, const fem::StepStatus& status);
  /// Flushes; throws std::runtime_error when the file could not be written.
  void close();

 private:
  std::filesystem::path m_file;
  std::ofstream m_out;
  std::size_t m_tools = 0;
};

/// `--vtu-series DIR [--vtu-every N]`: DIR/step_NNNNNN.vtu at step 0 and every N steps after,
/// and DIR/series.pvd listing them with their simulated times.
class VtuSeries {
 public:
  VtuSeries(std::filesystem::path dir, std::int64_t every);
  /// Writes the mesh when `state.step` is a multiple of `every`.
  void add(const SimState& state);
  /// Writes series.pvd; returns the number of VTU files.
  std::size_t close();

 private:
  std::filesystem::path m_dir;
  std::int64_t m_every;
  std::vector<std::pair<double, std::string>> m_written;  ///< (time s, file name)
};

}  // namespace serosa::app
