// --task NAME [--tasks FILE] on `serosa run` and `serosa headless`: the task's scene in place of
// the SCENE argument (trainee/task_list.h).
#pragma once

#include <filesystem>
#include <string>

#include <CLI/CLI.hpp>

#include "trainee/task_list.h"

namespace serosa::trainee {

struct TaskOption {
  std::string name;                                  ///< --task; empty: none
  std::string list = std::string(kDefaultTaskList);  ///< --tasks
};

/// Adds --task and --tasks to `cmd`.
void add_task_options(CLI::App& cmd, TaskOption& task);

/// The scene to run: `scene` (the SCENE argument), or the task's when --task names one.
/// InputError when both or neither are given, or the task is not in the list.
[[nodiscard]] std::filesystem::path scene_to_run(const std::string& scene, const TaskOption& task);

}  // namespace serosa::trainee
