// The report's "assessment": the session's metrics (the metrics stage's, and what the final mesh
// shows) scored against the scene's rubric (engine/scene/rubric.h, metrics/assessment.h).
#pragma once

#include <map>
#include <string>

#include <nlohmann/json.hpp>

#include "engine/scene/scene.h"
#include "engine/tet_mesh.h"
#include "metrics/metrics_stage.h"

namespace serosa::app {

/// Every value a rubric may name (docs/assessment.md), measured by `metrics` over the run and on
/// `mesh` at its end (pieces per group). groups: scene-wide group id -> name.
[[nodiscard]] std::map<std::string, double> session_values(
    const Scene& scene, const metrics::MetricsStage& metrics, const TetMesh& mesh,
    const std::map<int, std::string>& groups);

/// The assessment of the run, or null when the scene names no rubric or measures no metrics.
[[nodiscard]] nlohmann::json assessment_report(const Scene& scene,
                                               const metrics::MetricsStage* metrics,
                                               const TetMesh& mesh,
                                               const std::map<int, std::string>& groups);

/// The report's "metrics", "procedure" (the metrics' procedure block, at the top too: the report
/// contract names it there) and "assessment" blocks, as the run ended; none without a metrics
/// stage.
void add_metrics_blocks(nlohmann::json& report, const Scene& scene,
                        const metrics::MetricsStage* metrics, const TetMesh& mesh,
                        const std::map<int, std::string>& groups);

}  // namespace serosa::app
