// The cohort page's charts as inline SVG (no script, nothing fetched): a trainee's learning curve
// (score against their session number, one polyline per task in the task's colour, passes ringed
// in green, each task's pass score a dashed line) and the group's pass rate per task (bars).
#pragma once

#include <string>
#include <vector>

#include "trainee/cohort.h"

namespace serosa::trainee {

/// The trainee's learning curve; `tasks` (Cohort::tasks) gives each task its colour.
[[nodiscard]] std::string learning_curve_svg(const TraineeCohort& trainee,
                                             const std::vector<std::string>& tasks);

/// One bar per task: the share of the trainees who practised it that passed it at least once.
[[nodiscard]] std::string pass_rate_svg(const std::vector<TaskPassRate>& rates);

}  // namespace serosa::trainee
