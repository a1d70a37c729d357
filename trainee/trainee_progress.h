// A trainee's progress from their sessions (trainee/progress_db.h): per task, how many sessions,
// how many passed, the best and the last score, the pass score and the session that first passed;
// why each failed session failed; printed as a table, and drawn as a learning curve (score
// against the trainee's session number, one line per task, the passes marked, each task's pass
// score a dashed line) with gnuplot. Tasks are named by trainee/task_names.h before they get here.
#pragma once

#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "trainee/progress_db.h"

namespace serosa::trainee {

struct TaskProgress {
  std::string task;
  int sessions = 0;
  int passed = 0;
  std::optional<double> best;        ///< the highest score (none: the task scores nothing)
  std::optional<double> last;        ///< the latest session's score
  std::optional<int> first_passed;   ///< the task's session number (1-based) that first passed
  bool last_passed = false;          ///< the latest session passed
  std::optional<double> pass_score;  ///< the latest pass score its sessions were scored against
};

/// Per task, in the order the trainee first practised them.
[[nodiscard]] std::vector<TaskProgress> task_progress(const std::vector<SessionRecord>& sessions);

/// A pass score drawn as one dashed line for the tasks that share it.
struct PassLine {
  double score = 0.0;
  std::vector<std::size_t> tasks;  ///< indices into the TaskProgress list
  /// What the legend says: "pass 80, camera", or "pass 80, every task", "pass 80, 2 tasks".
  [[nodiscard]] std::string label(const std::vector<TaskProgress>& all) const;
};
/// The distinct pass scores of `tasks`, lowest first.
[[nodiscard]] std::vector<PassLine> pass_lines(const std::vector<TaskProgress>& tasks);

/// One reason of an assessment's `failed` list, short: "score 77 < 80",
/// "cut.collateral_m3 = 2.1e-06 m3 > 1e-06"; other text as it is.
[[nodiscard]] std::string short_reason(const std::string& reason);
/// What a reason is about, to count alike reasons together: the metric's name, or
/// "score under the pass score".
[[nodiscard]] std::string criterion_of(const std::string& reason);
/// Why the session failed, its reasons short and joined by "; "; empty when it passed or was not
/// scored.
[[nodiscard]] std::string why_failed(const SessionRecord& s);

/// The progress table and every session, as `serosa trainee NAME` prints them.
[[nodiscard]] std::string progress_text(const std::string& trainee,
                                        const std::vector<SessionRecord>& sessions);

/// Every trainee with their sessions and tasks, as `serosa trainee` without a name prints them.
[[nodiscard]] std::string trainees_text(const std::vector<SessionRecord>& all,
                                        const std::filesystem::path& db);

/// The colour (#rrggbb) the `index`th task is drawn in, in the plot and on the cohort's page.
[[nodiscard]] const char* task_colour(std::size_t index);

/// Draws the learning curve into `png` with `gnuplot` (its script and data in a temporary folder
/// that is removed). @throws std::runtime_error with gnuplot's own message when it fails or draws
/// nothing
void plot_learning_curve(const std::string& trainee, const std::vector<SessionRecord>& sessions,
                         const std::filesystem::path& png, const std::string& gnuplot = "gnuplot");

}  // namespace serosa::trainee
