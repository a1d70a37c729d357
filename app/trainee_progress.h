// A trainee's progress from their sessions (app/progress_db.h): per task, how many sessions, how
// many passed, the best and the last score and the session that first passed; printed as a table,
// and drawn as a learning curve (score against the trainee's session number, one line per task,
// the passes marked) with gnuplot.
#pragma once

#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "app/progress_db.h"

namespace serosa::app {

struct TaskProgress {
  std::string task;
  int sessions = 0;
  int passed = 0;
  std::optional<double> best;       ///< the highest score (none: the task scores nothing)
  std::optional<double> last;       ///< the latest session's score
  std::optional<int> first_passed;  ///< the task's session number (1-based) that first passed
};

/// Per task, in the order the trainee first practised them.
[[nodiscard]] std::vector<TaskProgress> task_progress(const std::vector<SessionRecord>& sessions);

/// The progress table and every session, as `serosa trainee NAME` prints them.
[[nodiscard]] std::string progress_text(const std::string& trainee,
                                        const std::vector<SessionRecord>& sessions);

/// Draws the learning curve into `png` with `gnuplot` (its script and data beside it, .gp and
/// .dat). @throws std::runtime_error with gnuplot's own message when it fails or draws nothing
void plot_learning_curve(const std::string& trainee, const std::vector<SessionRecord>& sessions,
                         const std::filesystem::path& png, const std::string& gnuplot = "gnuplot");

}  // namespace serosa::app
