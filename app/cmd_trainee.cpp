// serosa trainee NAME [--db FILE] [--plot PNG]: a trainee's progress (app/trainee_progress.h):
// per task the sessions, passes, best and last score and the first pass, then every session;
// --plot draws the learning curve with gnuplot. Exit codes: 0 done; 1 bad input (an unknown
// trainee, a locked, damaged or foreign database, gnuplot failing).
#include <cstdio>
#include <memory>
#include <stdexcept>

#include "app/command.h"
#include "app/progress_db.h"
#include "app/trainee_progress.h"
#include "engine/input_error.h"

namespace serosa::app {

void add_trainee_command(CLI::App& app, Action& action) {
  auto name = std::make_shared<std::string>();
  auto db = std::make_shared<std::string>();
  auto plot = std::make_shared<std::string>();
  CLI::App* cmd = app.add_subcommand("trainee", "A trainee's progress and learning curve");
  cmd->add_option("name", *name, "The trainee's name")->required();
  cmd->add_option("--db", *db,
                  "Progress database (default: $SEROSA_PROGRESS_DB, else "
                  "~/.local/share/serosa/progress.sqlite)");
  cmd->add_option("--plot", *plot, "Draw the learning curve into this PNG (gnuplot)");
  cmd->callback([&action, name, db, plot] {
    action = [name, db, plot] {
      const std::filesystem::path file =
          db->empty() ? default_progress_db() : std::filesystem::path(*db);
      if (!std::filesystem::exists(file))
        throw InputError(file.string(), 0, "no progress database here",
                         "a database a session with --trainee wrote (--db FILE)");
      ProgressDb progress(file);
      const std::vector<SessionRecord> sessions = progress.sessions(*name);
      if (sessions.empty()) {
        std::string known;
        for (const std::string& t : progress.trainees()) known += (known.empty() ? "" : ", ") + t;
        throw InputError(file.string(), 0, "no sessions of trainee '" + *name + "'",
                         "one of: " + (known.empty() ? std::string("(none yet)") : known));
      }
      std::printf("%s", progress_text(*name, sessions).c_str());
      if (!plot->empty()) {
        try {
          plot_learning_curve(*name, sessions, *plot);
        } catch (const std::runtime_error& e) {
          throw InputError(*plot, 0, e.what(), "gnuplot (gnuplot-nox) on the PATH");
        }
        std::printf("\nlearning curve: %s\n", plot->c_str());
      }
      return 0;
    };
  });
}

}  // namespace serosa::app
