// The cohort: every trainee's progress on every task, gathered from the progress database's
// sessions (trainee/progress_db.h) for the instructor's page (trainee/cohort_html.h) and
// spreadsheet (trainee/cohort_csv.h). Plain data, no files read: the sessions' tasks are named by
// trainee/task_names.h and ordered as the curriculum orders them.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "trainee/progress_db.h"
#include "trainee/task_names.h"
#include "trainee/trainee_progress.h"

namespace serosa::trainee {

struct TraineeCohort {
  std::string name;
  std::vector<SessionRecord> sessions;  ///< oldest first; session number = index + 1
  std::vector<TaskProgress> tasks;      ///< the tasks practised, in Cohort::tasks' order
  /// The trainee's progress on `task`; none when they never practised it.
  [[nodiscard]] const TaskProgress* on(const std::string& task) const;
};

struct TaskPassRate {
  std::string task;
  int trainees = 0;         ///< who practised it
  int trainees_passed = 0;  ///< who passed it at least once
  int sessions = 0;
  int sessions_passed = 0;
  std::optional<double> pass_score;  ///< the latest pass score its sessions were scored against
};

/// A criterion the sessions missed: a rubric metric on the wrong side of its limit, or the score
/// under the pass score.
struct CriterionCount {
  std::string criterion;  ///< the metric's name, or "score under the pass score"
  int sessions = 0;       ///< sessions that missed it (assessment failed or below_threshold)
  int failing = 0;        ///< of those, the sessions it failed (assessment failed)
  std::vector<std::string> tasks;  ///< the tasks it was missed in, in the curriculum's order
};

struct Cohort {
  std::vector<std::string> tasks;        ///< every task with sessions, curriculum order
  std::vector<TraineeCohort> trainees;   ///< by name
  std::vector<TaskPassRate> pass_rates;  ///< one per task, as `tasks`
  std::vector<CriterionCount> criteria;  ///< most often missed first
  int sessions = 0;
  int reasons_unknown = 0;  ///< failed sessions whose reasons had gone (trainee/progress_db.h)
};

/// Gathers `sessions` (any order within a trainee's: oldest first is kept) into the cohort.
[[nodiscard]] Cohort gather_cohort(std::vector<SessionRecord> sessions, const TaskNames& names);

}  // namespace serosa::trainee
