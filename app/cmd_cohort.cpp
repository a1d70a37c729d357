// serosa cohort [--db FILE] --html DIR [--csv FILE] [--tasks FILE]: the instructor's page of the
// whole group (trainee/cohort_html.h) as DIR/index.html, and with --csv the trainee x task table
// for a spreadsheet (trainee/cohort_csv.h). Tasks are named as `serosa tasks` names them. A
// recording or report that moved is a warning naming it, shown as missing on the page, which is
// written all the same. Exit codes: 0 written; 1 bad input (a missing, locked, damaged or foreign
// database, a folder or file that cannot be written).
#include <cstdio>
#include <fstream>
#include <memory>

#include "app/command.h"
#include "engine/input_error.h"
#include "trainee/cohort.h"
#include "trainee/cohort_csv.h"
#include "trainee/cohort_html.h"
#include "trainee/progress_db.h"
#include "trainee/task_names.h"
#include "trainee/trainee_session.h"

namespace serosa::app {

using namespace serosa::trainee;

namespace {

struct CohortArgs {
  std::string db;
  std::string html;
  std::string csv;
  std::string tasks;
};

void write_file(const std::filesystem::path& file, const std::string& text, const char* what) {
  std::ofstream out(file, std::ios::binary);
  out << text;
  if (!out)
    throw InputError(file.string(), 0, std::string("cannot write the ") + what, "a writable file");
}

void warn_missing(const Cohort& cohort) {
  for (const std::string& f : missing_files(cohort))
    std::fprintf(stderr, "warning: %s\n",
                 InputError(f, 0, "not there: moved or deleted since its session was filed",
                            "the recording or report the progress database names; shown as "
                            "missing on the page")
                     .what());
}

int write_cohort(const CohortArgs& a) {
  const std::filesystem::path db =
      a.db.empty() ? default_progress_db() : std::filesystem::path(a.db);
  const std::filesystem::path dir = a.html;
  std::vector<SessionRecord> sessions = ProgressDb(db, ProgressDb::Open::existing).all_sessions();
  const Cohort cohort = gather_cohort(std::move(sessions), load_task_names(a.tasks));
  warn_missing(cohort);
  std::error_code ec;
  std::filesystem::create_directories(dir, ec);
  if (!std::filesystem::is_directory(dir))
    throw InputError(dir.string(), 0, "cannot make the page's folder",
                     "a folder that can be written (--html DIR)");
  const PageContext context{dir, std::filesystem::absolute(db).lexically_normal(), utc_now()};
  write_file(dir / "index.html", cohort_html(cohort, context), "cohort page");
  std::printf("cohort: %zu trainees, %d sessions, %zu tasks\npage: %s\n", cohort.trainees.size(),
              cohort.sessions, cohort.tasks.size(), (dir / "index.html").c_str());
  if (!a.csv.empty()) {
    write_file(a.csv, cohort_csv(cohort), "trainee x task table");
    std::printf("table: %s\n", a.csv.c_str());
  }
  return 0;
}

}  // namespace

void add_cohort_command(CLI::App& app, Action& action) {
  auto args = std::make_shared<CohortArgs>();
  CLI::App* cmd =
      app.add_subcommand("cohort", "The instructor's page of every trainee's progress (HTML, CSV)");
  cmd->add_option("--db", args->db,
                  "Progress database (default: $SEROSA_PROGRESS_DB, else "
                  "~/.local/share/serosa/progress.sqlite)");
  cmd->add_option("--html", args->html, "Write the page into this folder (DIR/index.html)")
      ->required();
  cmd->add_option("--csv", args->csv, "Also write the trainee x task table as CSV");
  cmd->add_option("--tasks", args->tasks,
                  "The task list that names the tasks (default: config/tasks.toml when present)");
  cmd->callback([&action, args] { action = [args] { return write_cohort(*args); }; });
}

}  // namespace serosa::app
