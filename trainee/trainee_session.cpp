#include "trainee/trainee_session.h"

#include <algorithm>
#include <cctype>
#include <ctime>

#include "engine/input_error.h"
#include "trainee/progress_db.h"
#include "trainee/task_names.h"

namespace serosa::trainee {

std::string utc_now() {
  const std::time_t t = std::time(nullptr);
  std::tm tm{};
  gmtime_r(&t, &tm);
  char buf[32];
  std::strftime(buf, sizeof buf, "%Y-%m-%dT%H:%M:%SZ", &tm);
  return buf;
}

void check_trainee_name(const std::string& name) {
  const bool ok = !name.empty() && name.size() <= 64 && name.front() != '.' &&
                  std::all_of(name.begin(), name.end(), [](char c) {
                    return std::isalnum(static_cast<unsigned char>(c)) != 0 || c == ' ' ||
                           c == '-' || c == '_' || c == '.';
                  });
  if (!ok)
    throw InputError("--trainee", 0, "'" + name + "' is not a trainee's name",
                     "1-64 letters, digits, spaces, '-', '_' or '.', not starting with '.'");
}

std::filesystem::path trainee_recording(const std::filesystem::path& db, const std::string& trainee,
                                        const std::string& task, const std::string& started_utc) {
  std::string stamp = started_utc;
  std::replace(stamp.begin(), stamp.end(), ':', '-');
  const std::filesystem::path folder = db.parent_path() / "recordings" / trainee;
  std::filesystem::path p = folder / (task + "_" + stamp + ".lapr");
  // Two sessions started in the same second must not share (and overwrite) a recording.
  for (int k = 2; std::filesystem::exists(p); ++k)
    p = folder / (task + "_" + stamp + "_" + std::to_string(k) + ".lapr");
  return p;
}

void add_trainee_options(CLI::App& cmd, TraineeOptions& options) {
  cmd.add_option("--trainee", options.name,
                 "File the session in this trainee's progress (recorded, with its report, beside "
                 "the database unless --record and --report are given)");
  cmd.add_option("--db", options.db,
                 "Progress database for --trainee (default: $SEROSA_PROGRESS_DB, else "
                 "~/.local/share/serosa/progress.sqlite)");
}

std::optional<TraineeSession> begin_trainee_session(const TraineeOptions& options,
                                                    const std::filesystem::path& scene,
                                                    std::optional<std::filesystem::path>& record,
                                                    std::optional<std::filesystem::path>& report) {
  if (options.name.empty()) return std::nullopt;
  check_trainee_name(options.name);
  TraineeSession s{options.name,
                   options.db.empty() ? default_progress_db() : std::filesystem::path(options.db),
                   utc_now()};
  if (!record) {
    record = trainee_recording(s.db, s.trainee, task_name_for_scene(scene), s.started_utc);
    std::filesystem::create_directories(record->parent_path());
  }
  if (!report) {  // beside the recording: the progress points at both
    report = *record;
    report->replace_extension(".json");
  }
  return s;
}

void file_session(const TraineeSession& session, const std::filesystem::path& scene,
                  const nlohmann::json& report,
                  const std::optional<std::filesystem::path>& recording,
                  const std::optional<std::filesystem::path>& report_file) {
  SessionRecord r;
  r.trainee = session.trainee;
  r.task = task_name_for_scene(scene);  // the database stays readable without the task list
  r.scene = std::filesystem::absolute(scene).lexically_normal().string();
  r.started_utc = session.started_utc;
  r.simulated_s = report.value("simulated_time_s", 0.0);
  if (const auto a = report.find("assessment"); a != report.end() && a->is_object())
    set_assessment(r, *a);
  if (recording) r.recording = std::filesystem::absolute(*recording).lexically_normal().string();
  if (report_file) r.report = std::filesystem::absolute(*report_file).lexically_normal().string();
  try {
    ProgressDb(session.db).add(r);
  } catch (const InputError& e) {
    std::string kept = "; the session is not in the progress, and is kept: recording ";
    kept += r.recording.empty() ? "(none)" : r.recording;
    kept += ", report " + (r.report.empty() ? std::string("(printed only)") : r.report);
    throw InputError(e.file(), e.line(), e.message() + kept, e.expected());
  }
}

}  // namespace serosa::trainee
