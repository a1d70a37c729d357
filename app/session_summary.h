// The end-of-session summary the trainee sees, from the report's assessment (docs/assessment.md).
#pragma once

#include <nlohmann/json.hpp>

#include "render/session_summary.h"

namespace serosa::app {

/// The summary of `assessment` (the report's "assessment" object): its title, score, pass, the
/// GOALS domains in words ("depth perception"), why it failed and what is below its limits.
[[nodiscard]] render::SessionSummary session_summary(const nlohmann::json& assessment);

}  // namespace serosa::app
