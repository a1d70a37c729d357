// The cohort's trainee x task table for a spreadsheet: one row per trainee and task (every task
// any trainee practised, so the grid is whole), RFC 4180 quoting. Columns: trainee, task,
// sessions, best, last (scores 0-100, one decimal; empty when none), passed (yes when any session
// passed), last_passed (yes when the latest did), passes (sessions passed), pass_score.
#pragma once

#include <string>

#include "trainee/cohort.h"

namespace serosa::trainee {

[[nodiscard]] std::string cohort_csv(const Cohort& cohort);

/// One CSV field: as it is, or in double quotes (quotes doubled) when it holds a comma, a quote
/// or a line break.
[[nodiscard]] std::string csv_field(const std::string& text);

}  // namespace serosa::trainee
