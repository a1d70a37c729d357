// The "preset" block of a run's report: what the scene's quality or accuracy_target
// chose from the measured curves (engine/scene/presets.h), what that choice costs and delivers on
// the reference scene it was measured on, and the solver settings the run actually used (explicit
// [solver] and [render] keys win over the preset).
#pragma once

#include <nlohmann/json.hpp>
#include <optional>

#include "engine/scene/scene.h"

namespace serosa::app {

/// The block, or nullopt when the scene names neither quality nor accuracy_target.
[[nodiscard]] std::optional<nlohmann::json> preset_report(const Scene& scene);

/// The solver settings a run used: kind, tolerance, max_iterations.
[[nodiscard]] nlohmann::json solver_report(const SolverSettings& solver);

}  // namespace serosa::app
