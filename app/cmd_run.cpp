// serosa run SCENE: the trainee session in a window.
#include <cstdlib>
#include <fstream>
#include <memory>
#include <string>

#include <nlohmann/json.hpp>

#include "app/command.h"
#include "app/emulated_rig_process.h"
#include "app/progress_db.h"
#include "app/session.h"
#include "app/trainee_session.h"
#include "engine/input_error.h"
#include "engine/scene.h"

namespace serosa::app {

void add_run_command(CLI::App& app, Action& action) {
  auto scene = std::make_shared<std::string>();
  auto seconds = std::make_shared<double>(0.0);
  auto snapshot = std::make_shared<std::string>();
  CLI::App* cmd = app.add_subcommand("run", "The trainee session: a window, the rig or the mouse");
  cmd->add_option("scene", *scene, "Scene TOML file")->required();
  cmd->add_option("--seconds", *seconds, "Close the window after this much wall time (0: never)");
  auto summary = std::make_shared<double>(0.0);
  cmd->add_option("--summary-seconds", *summary,
                  "With --seconds: show the assessment's summary this long after the session");
  cmd->add_option("--snapshot", *snapshot,
                  "Also write the last picture drawn to this PNG (for checks and bug reports)");
  auto record = std::make_shared<std::string>();
  auto report = std::make_shared<std::string>();
  cmd->add_option("--record", *record,
                  "Record the session (.lapr) here (default: the scene's [record] path)");
  cmd->add_option("--report", *report,
                  "Write a JSON report at the end (frames, steps, haptic telemetry, metrics)");
  auto trainee = std::make_shared<std::string>();
  auto db = std::make_shared<std::string>();
  cmd->add_option("--trainee", *trainee,
                  "File the session in this trainee's progress (recorded, with its report, "
                  "beside the database unless --record and --report are given)");
  cmd->add_option("--db", *db,
                  "Progress database for --trainee (default: $SEROSA_PROGRESS_DB, "
                  "else ~/.local/share/serosa/progress.sqlite)");
  auto path = std::make_shared<std::string>();
  cmd->add_option("--path", *path,
                  "Tool path CSV every scripted tool plays (default: the scripted instruments "
                  "follow the rig when it is plugged in, else the mouse)");
  cmd->callback([&action, scene, seconds, snapshot, record, report, path, summary, trainee, db] {
    action = [scene, seconds, snapshot, record, report, path, summary, trainee, db] {
      const char* x = std::getenv("DISPLAY");
      const char* wl = std::getenv("WAYLAND_DISPLAY");
      if ((x == nullptr || *x == '\0') && (wl == nullptr || *wl == '\0'))
        throw InputError(*scene, 0, "serosa run needs a display and none is set",
                         "DISPLAY or WAYLAND_DISPLAY; without one use `serosa headless`");
      run_under_umockdev_if_rig_emulated(load_scene(*scene));
      SessionOptions so;
      so.seconds = *seconds;
      so.snapshot = *snapshot;
      so.summary_seconds = *summary;
      if (!record->empty()) so.record = *record;
      if (!report->empty()) so.report = *report;
      if (!path->empty()) so.tool_path = *path;
      if (trainee->empty()) return run_session(*scene, so);
      check_trainee_name(*trainee);
      const std::string started = utc_now();
      const std::filesystem::path db_file =
          db->empty() ? default_progress_db() : std::filesystem::path(*db);
      if (!so.record) {
        so.record =
            trainee_recording(db_file, *trainee, std::filesystem::path(*scene).stem(), started);
        std::filesystem::create_directories(so.record->parent_path());
      }
      if (!so.report) {  // the report beside the recording: the progress points at both
        so.report = *so.record;
        so.report->replace_extension(".json");
      }
      const int code = run_session(*scene, so);
      nlohmann::json rep;
      std::ifstream(*so.report) >> rep;
      file_session(db_file, *trainee, *scene, started, rep, so.record, so.report);
      return code;
    };
  });
}

}  // namespace serosa::app
