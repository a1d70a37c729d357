// A run's debrief from its report (docs/assessment.md): what the trainee sees when a session ends
// and what the instructor's replay shows beside the picture, laid out the same way.
#pragma once

#include <vector>

#include <nlohmann/json.hpp>

#include "app/failure_marks.h"
#include "render/session_summary.h"

namespace serosa::app {

/// The debrief of `report` (its "assessment", "metrics" and procedure): title, score, pass, the
/// GOALS domains in words ("depth perception"), why it failed in words (the critical criteria and
/// the score; the other failed criteria under "to work on"), the procedure's steps and the
/// rubric's metrics by domain. `failed` (app/failure_marks.h) gives the failures with their times
/// (the replay's); without it they are taken from the report alone, without times.
[[nodiscard]] render::SessionSummary session_summary(const nlohmann::json& report,
                                                     const std::vector<Failure>* failed = nullptr);

}  // namespace serosa::app
