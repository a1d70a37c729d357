// serosa trainee [NAME] [--db FILE] [--tasks FILE] [--plot PNG]: a trainee's progress
// (trainee/trainee_progress.h): per task the sessions, passes, best and last score, the pass score
// and the first pass, then every session and why each failed one failed; --plot draws the learning
// curve with gnuplot. Without a name: every trainee with their sessions, and where to go next.
// Tasks are named as `serosa tasks` names them (trainee/task_names.h). Exit codes: 0 done; 1 bad
// input (a missing, locked, damaged or foreign database, an unknown trainee, gnuplot failing).
#include <cstdio>
#include <memory>
#include <stdexcept>

#include "app/command.h"
#include "engine/input_error.h"
#include "trainee/progress_db.h"
#include "trainee/task_names.h"
#include "trainee/trainee_progress.h"

namespace serosa::app {

using namespace serosa::trainee;

namespace {

struct TraineeArgs {
  std::string name;
  std::string db;
  std::string tasks;
  std::string plot;
};

int show_trainee(const TraineeArgs& a) {
  const std::filesystem::path file =
      a.db.empty() ? default_progress_db() : std::filesystem::path(a.db);
  ProgressDb progress(file, ProgressDb::Open::existing);
  const TaskNames names = load_task_names(a.tasks);
  if (a.name.empty()) {
    std::vector<SessionRecord> all = progress.all_sessions();
    name_tasks(all, names);
    std::fputs(trainees_text(all, file).c_str(), stdout);
    return 0;
  }
  std::vector<SessionRecord> sessions = progress.sessions(a.name);
  if (sessions.empty()) {
    std::string known;
    for (const std::string& t : progress.trainees())
      known.append(known.empty() ? "" : ", ").append(t);
    throw InputError(file.string(), 0, std::string("no sessions of trainee '") + a.name + "'",
                     "one of: " + (known.empty() ? std::string("(none yet)") : known));
  }
  name_tasks(sessions, names);
  std::fputs(progress_text(a.name, sessions).c_str(), stdout);
  if (!a.plot.empty()) {
    try {
      plot_learning_curve(a.name, sessions, a.plot);
    } catch (const std::runtime_error& e) {
      throw InputError(a.plot, 0, e.what(), "gnuplot (gnuplot-nox) on the PATH");
    }
    std::printf("\nlearning curve: %s\n", a.plot.c_str());
  }
  return 0;
}

}  // namespace

void add_trainee_command(CLI::App& app, Action& action) {
  auto args = std::make_shared<TraineeArgs>();
  CLI::App* cmd = app.add_subcommand("trainee", "A trainee's progress and learning curve");
  cmd->add_option("name", args->name, "The trainee's name (none: list the trainees)");
  cmd->add_option("--db", args->db,
                  "Progress database (default: $SEROSA_PROGRESS_DB, else "
                  "~/.local/share/serosa/progress.sqlite)");
  cmd->add_option("--tasks", args->tasks,
                  "The task list that names the tasks (default: config/tasks.toml when present)");
  cmd->add_option("--plot", args->plot, "Draw the learning curve into this PNG (gnuplot)");
  cmd->callback([&action, args] { action = [args] { return show_trainee(*args); }; });
}

}  // namespace serosa::app
