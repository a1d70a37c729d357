#include "trainee/task_option.h"

#include "engine/input_error.h"

namespace serosa::trainee {

void add_task_options(CLI::App& cmd, TaskOption& task) {
  cmd.add_option("--task", task.name,
                 "Run this task of the curriculum instead of a SCENE (`serosa tasks` lists them)");
  cmd.add_option("--tasks", task.list, "The task list (default: config/tasks.toml)");
}

std::filesystem::path scene_to_run(const std::string& scene, const TaskOption& task) {
  if (task.name.empty()) {
    if (scene.empty())
      throw InputError("command line", 0, "no scene to run", "a SCENE file or --task NAME");
    return scene;
  }
  if (!scene.empty())
    throw InputError("command line", 0, "both a SCENE and --task " + task.name, "one of them");
  const std::vector<Task> tasks = load_tasks(task.list);
  return find_task(tasks, task.name, task.list).scene;
}

}  // namespace serosa::trainee
