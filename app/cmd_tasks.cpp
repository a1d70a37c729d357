// serosa tasks [--tasks FILE]: the curriculum, a task a line, basic first.
#include <cstdio>
#include <memory>

#include "app/command.h"
#include "trainee/task_list.h"

namespace serosa::app {

using namespace serosa::trainee;

void add_tasks_command(CLI::App& app, Action& action) {
  auto list = std::make_shared<std::string>(kDefaultTaskList);
  CLI::App* cmd = app.add_subcommand("tasks", "The curriculum's tasks (run one: --task NAME)");
  cmd->add_option("--tasks", *list, "The task list (default: config/tasks.toml)");
  cmd->callback([&action, list] {
    action = [list] {
      std::fputs(tasks_text(load_tasks(*list)).c_str(), stdout);
      return 0;
    };
  });
}

}  // namespace serosa::app
