// The curriculum (config/tasks.toml): tasks from basic to procedural, each a scene with its own
// rubric ([metrics] rubric) and, to validate that rubric, an expert's and a novice's scripted path
// (the expert passes, the novice fails: tests/app/test_tasks.cpp). `serosa tasks` lists them;
// `serosa run --task NAME` and `serosa headless --task NAME` run one (docs/assessment.md).
#pragma once

#include <cstdint>
#include <filesystem>
#include <string>
#include <string_view>
#include <vector>

namespace serosa::trainee {

/// Where `serosa` looks for the task list unless told (--tasks): relative to the working folder.
inline constexpr std::string_view kDefaultTaskList = "config/tasks.toml";

struct Task {
  std::string name;               ///< what --task takes: lower case, digits and '-'
  std::string title;              ///< what the trainee reads
  std::string skill;              ///< the skill it trains, one line
  int level = 1;                  ///< 1 basic .. 5 the full procedure
  std::filesystem::path scene;    ///< its scene (absolute: resolved against the list's folder)
  std::filesystem::path expert;   ///< an expert's scripted path (absolute)
  std::filesystem::path novice;   ///< a novice's scripted path (absolute)
  std::int64_t expert_steps = 0;  ///< steps the expert's path takes
  std::int64_t novice_steps = 0;  ///< steps the novice's path takes
};

/// The tasks of `file`, by level then in the file's order. InputError naming the line on an
/// unknown or missing key, a repeated or malformed name, a level outside 1..5, a file that does
/// not exist.
[[nodiscard]] std::vector<Task> load_tasks(const std::filesystem::path& file);

/// The task called `name`; InputError listing the names when there is none.
[[nodiscard]] const Task& find_task(const std::vector<Task>& tasks, std::string_view name,
                                    const std::filesystem::path& file);

/// One line a task: "1  cut-line      Cut along the planned line  (config/tasks/cut_line.toml)".
[[nodiscard]] std::string tasks_text(const std::vector<Task>& tasks);

}  // namespace serosa::trainee
