// Task names as `serosa tasks` says them ("cut-line"), for the sessions in the progress database:
// a session runs a scene (config/cut_line.toml), and the curriculum (config/tasks.toml,
// trainee/task_list.h) names the task that scene is. A scene that is no task of the list keeps its
// file's stem. `serosa trainee`, `serosa cohort` and the filing of a session name tasks this way.
#pragma once

#include <filesystem>
#include <string>
#include <vector>

#include "trainee/progress_db.h"
#include "trainee/task_list.h"

namespace serosa::trainee {

class TaskNames {
 public:
  TaskNames() = default;  ///< no task list: the names the database holds are kept
  explicit TaskNames(std::vector<Task> tasks) : m_tasks(std::move(tasks)) {}

  /// The session's task: the list's task whose scene it ran (the same file, else the same file
  /// name's stem), else the task its database row names, else that name as it is.
  [[nodiscard]] std::string of(const std::filesystem::path& scene, const std::string& stored) const;
  /// Where the task stands in the curriculum (basic first); tasks not in it after every one.
  [[nodiscard]] std::size_t order(const std::string& name) const;

 private:
  std::vector<Task> m_tasks;
};

/// The names for showing progress: from `list` when given (an InputError when it does not load),
/// else from config/tasks.toml under the working folder when it is there, else none.
[[nodiscard]] TaskNames load_task_names(const std::string& list);

/// The task name a session of `scene` is filed under: the task list beside the scene (its
/// folder's tasks.toml, as config/ holds both) or config/tasks.toml under the working folder
/// names it; else the scene's stem.
[[nodiscard]] std::string task_name_for_scene(const std::filesystem::path& scene);

/// Every session's task named by `names` (SessionRecord::task replaced).
void name_tasks(std::vector<SessionRecord>& sessions, const TaskNames& names);

}  // namespace serosa::trainee
