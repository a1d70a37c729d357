// serosa run SCENE|--task NAME: the trainee session in a window.
#include <cstdlib>
#include <fstream>
#include <memory>
#include <string>

#include <nlohmann/json.hpp>

#include "app/command.h"
#include "app/emulated_rig_process.h"
#include "app/session.h"
#include "engine/input_error.h"
#include "engine/scene/scene.h"
#include "trainee/help_seen.h"
#include "trainee/task_option.h"
#include "trainee/trainee_session.h"

namespace serosa::app {

using namespace serosa::trainee;

void add_run_command(CLI::App& app, Action& action) {
  auto scene = std::make_shared<std::string>();
  auto seconds = std::make_shared<double>(0.0);
  auto snapshot = std::make_shared<std::string>();
  CLI::App* cmd = app.add_subcommand("run", "The trainee session: a window, the rig or the mouse");
  auto task = std::make_shared<TaskOption>();
  cmd->add_option("scene", *scene, "Scene TOML file (or --task NAME)");
  add_task_options(*cmd, *task);
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
  auto trainee = std::make_shared<TraineeOptions>();
  add_trainee_options(*cmd, *trainee);
  auto view_log = std::make_shared<std::string>();
  cmd->add_option("--view-log", *view_log,
                  "JSON lines: where each frame drew the instruments, the guide and the organs "
                  "(window pixels), for studies and scripted checks");
  auto path = std::make_shared<std::string>();
  cmd->add_option("--path", *path,
                  "Tool path CSV every scripted tool plays (default: the scripted instruments "
                  "follow the rig when it is plugged in, else the mouse)");
  cmd->callback([&action, scene, seconds, snapshot, record, report, path, summary, trainee, task,
                 view_log] {
    action = [scene, seconds, snapshot, record, report, path, summary, trainee, task, view_log] {
      *scene = scene_to_run(*scene, *task).string();
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
      so.trainee = trainee->name;
      if (!view_log->empty()) so.view_log = *view_log;
      so.help_file = help_seen_file(trainee->db);
      const std::optional<TraineeSession> kept =
          begin_trainee_session(*trainee, *scene, so.record, so.report);
      const int code = run_session(*scene, so);
      if (!kept) return code;
      nlohmann::json rep;  // the session's report, as it was written
      std::ifstream(*so.report) >> rep;
      file_session(*kept, *scene, rep, so.record, so.report);
      return code;
    };
  });
}

}  // namespace serosa::app
