// The curriculum (trainee/task_list.h, config/tasks.toml): every shipped task's expert path passes
// its rubric and its novice path fails it; `serosa tasks` lists them, basic first; `--task NAME`
// runs the task's scene; a bad task list or name is a clear error naming the line.
#include <gtest/gtest.h>

#include <fstream>
#include <string>

#include <nlohmann/json.hpp>

#include "app/headless.h"
#include "app_test_util.h"
#include "engine/input_error.h"
#include "engine/shell_command.h"
#include "trainee/task_list.h"

namespace serosa::app {
namespace {

using namespace serosa::trainee;

using namespace serosa::app::testing;

nlohmann::json run_task_path(const Task& t, const fs::path& path, std::int64_t steps) {
  HeadlessOptions o;
  o.scene = t.scene;
  o.tool_path = path;
  o.steps = steps;
  o.progress = false;
  return run_headless(o);
}

TEST(Tasks, TheShippedListLoadsBasicFirstWithEveryFileThere) {
  const std::vector<Task> tasks = load_tasks(source("config/tasks.toml"));
  ASSERT_GE(tasks.size(), 2u);
  for (std::size_t i = 0; i < tasks.size(); ++i) {
    EXPECT_TRUE(fs::is_regular_file(tasks[i].scene)) << tasks[i].name;
    if (i > 0) {
      EXPECT_GE(tasks[i].level, tasks[i - 1].level);
    }
  }
  EXPECT_EQ(find_task(tasks, "transection", "t").scene, source("config/transection.toml"));
  EXPECT_EQ(find_task(tasks, "appendectomy", "t").scene, source("config/appendectomy.toml"));
}

// Each task: its expert passes and its novice fails its own rubric (the cut-line task's and the
// transection's novice strays 4 mm towards the base, a critical collateral cut; the
// appendectomy's misses the clip, and its hook cuts the unsecured artery).
TEST(Tasks, EveryExpertPassesAndEveryNoviceFails) {
  for (const Task& t : load_tasks(source("config/tasks.toml"))) {
    SCOPED_TRACE(t.name);
    const nlohmann::json expert = run_task_path(t, t.expert, t.expert_steps);
    ASSERT_TRUE(expert.contains("assessment")) << "no rubric in " << t.scene;
    EXPECT_TRUE(expert["assessment"]["passed"].get<bool>()) << expert["assessment"].dump(1);
#if !defined(__SANITIZE_ADDRESS__)  // the 12 s novice runs: ASan+UBSan is ~15x slower
    const nlohmann::json novice = run_task_path(t, t.novice, t.novice_steps);
    EXPECT_FALSE(novice["assessment"]["passed"].get<bool>()) << novice["assessment"].dump(1);
    EXPECT_LT(novice["assessment"]["score"].get<double>(),
              expert["assessment"]["score"].get<double>());
#endif
  }
}

TEST(Tasks, TheCommandLineListsThemAndRunsOneByName) {
  const std::string list = shell_quote(source("config/tasks.toml").string());
  const CliResult tasks = run_serosa("tasks --tasks " + list);
  ASSERT_EQ(tasks.code, 0) << tasks.out;
  EXPECT_LT(tasks.out.find("cut-line"), tasks.out.find("appendectomy")) << tasks.out;
  const fs::path dir = out_dir("tasks_cli");
  const CliResult run = run_serosa("headless --task cut-line --tasks " + list + " --steps 40" +
                                   " --report " + shell_quote((dir / "r.json").string()));
  ASSERT_EQ(run.code, 0) << run.out;
  nlohmann::json r;
  std::ifstream(dir / "r.json") >> r;
  EXPECT_EQ(r["scene"], source("config/cut_line.toml").string());
  // A name not in the list, or a task and a scene both: exit 1, saying what.
  const CliResult unknown = run_serosa("headless --task cutline --tasks " + list);
  EXPECT_EQ(unknown.code, 1);
  EXPECT_NE(unknown.out.find("no task named 'cutline'"), std::string::npos) << unknown.out;
  EXPECT_NE(unknown.out.find("cut-line"), std::string::npos) << unknown.out;  // the names
  const CliResult both =
      run_serosa("headless " + shell_quote(source("config/transection.toml").string()) +
                 " --task cut-line --tasks " + list);
  EXPECT_EQ(both.code, 1);
  EXPECT_NE(both.out.find("both a SCENE and --task"), std::string::npos) << both.out;
}

// A broken task list names the line and the key.
TEST(Tasks, ABadListIsAClearErrorNamingTheLine) {
  const fs::path dir = out_dir("tasks_bad");
  const std::string good =
      "[[task]]\nname = \"a\"\ntitle = \"A\"\nlevel = 1\n"
      "scene = \"s.toml\"\nexpert = \"e.csv\"\nexpert_steps = 10\n"
      "novice = \"n.csv\"\nnovice_steps = 10\n";
  for (const char* f : {"s.toml", "e.csv", "n.csv"}) std::ofstream(dir / f) << "x\n";
  struct Case {
    std::string text, says;
    int line;
  };
  const std::vector<Case> cases = {
      {good + "colour = \"red\"\n", "task[0].colour: unknown key", 10},
      {"[[task]]\nname = \"a\"\n", "task[0]: missing key 'title'", 1},
      {good + good, "a second task named 'a'", 11},
      {"[[task]]\nname = \"A b\"\n", "'A b' is not a task name", 2},
      {std::string(good).replace(good.find("level = 1"), 9, "level = 9"), "task[0].level", 4},
      {std::string(good).replace(good.find("e.csv"), 5, "gone.csv"), "no such file", 6},
      {"task = 3\n", "no [[task]] tables", 0},
      {"[[task]\n", "TOML syntax error", 1},
  };
  for (const Case& c : cases) {
    SCOPED_TRACE(c.text);
    std::ofstream(dir / "tasks.toml") << c.text;
    try {
      (void)load_tasks(dir / "tasks.toml");
      ADD_FAILURE() << "no error";
    } catch (const InputError& e) {
      EXPECT_NE(std::string(e.what()).find(c.says), std::string::npos) << e.what();
      EXPECT_EQ(e.line(), c.line) << e.what();
    }
  }
  EXPECT_THROW((void)load_tasks(dir / "missing.toml"), InputError);
}

}  // namespace
}  // namespace serosa::app
