// What a run did that the scene did not ask for, said out loud: steps the solver left above its
// tolerance, steps that gained energy or were rejected, fixed selections that picked no node, a
// tool path given in place of the scene's that the scene's steps cut off.
// `serosa headless` prints each on stderr as "warning: ...", lists them in the report
// ("warnings") and, with --strict, exits 4 (docs/headless-report.md).
#pragma once

#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "app/assemble_state.h"
#include "engine/scene/scene.h"
#include "fem/fem_stage.h"

namespace serosa::app {

struct RunWarning {
  /// "not_converged" | "energy_gain" | "rejected" | "empty_selection" | "path_cut_short"
  std::string kind;
  std::string text;  ///< one line: what, where first, the figures, what to change
};

/// Fixed selections that picked no node: known before the first step.
[[nodiscard]] std::vector<RunWarning> selection_warnings(const Scene& scene,
                                                         const AssembledScene& assembled);

/// The tool path `csv` (--path, played by the scene's scripted tools) when it lasts longer than
/// the run's `steps` (the scene's [headless] steps): the run stops before its end. None when it
/// ends first (the tools then rest at its last pose, as a path means them to). Known before the
/// first step. Throws InputError when the file does not read as a tool path.
[[nodiscard]] std::vector<RunWarning> path_warnings(const Scene& scene,
                                                    const std::filesystem::path& csv,
                                                    std::int64_t steps);

/// What the FEM stage counted over the run.
[[nodiscard]] std::vector<RunWarning> solver_warnings(const SolverSettings& solver,
                                                      const fem::FemStageStats& stats);

/// Prints each as "warning: TEXT" on stderr.
void print_warnings(const std::vector<RunWarning>& warnings);

/// The report's "warnings": [{"kind", "text"}, ...].
[[nodiscard]] nlohmann::json warnings_json(const std::vector<RunWarning>& warnings);

/// The report's "fixed": {"nodes": total, "organs": [{"organ", "box", "groups", "nodes",
/// "total"}, ...]} (a selection the organ does not give is absent).
[[nodiscard]] nlohmann::json fixed_json(const AssembledScene& assembled);

}  // namespace serosa::app
