// Keeping a trainee's session: where it is recorded when no --record is given, and filing it in
// the progress database once its recording and report are written (trainee/progress_db.h).
#pragma once

#include <filesystem>
#include <optional>
#include <string>

#include <CLI/CLI.hpp>
#include <nlohmann/json.hpp>

namespace serosa::trainee {

/// `--trainee NAME` and `--db FILE`, as `serosa run` and `serosa headless` take them.
struct TraineeOptions {
  std::string name;  ///< empty: the session is not filed
  std::string db;    ///< empty: default_progress_db()
};
void add_trainee_options(CLI::App& cmd, TraineeOptions& options);

/// A session being kept for a trainee: where it is filed and when it started.
struct TraineeSession {
  std::string trainee;
  std::filesystem::path db;
  std::string started_utc;
};

/// When `options` name a trainee: checks the name, and sends the recording and the report beside
/// the database where `record` and `report` are not given (their folder made). None otherwise.
[[nodiscard]] std::optional<TraineeSession> begin_trainee_session(
    const TraineeOptions& options, const std::filesystem::path& scene,
    std::optional<std::filesystem::path>& record, std::optional<std::filesystem::path>& report);

/// Now, UTC, ISO 8601 to the second: "2026-12-03T14:25:00Z".
[[nodiscard]] std::string utc_now();

/// @throws InputError when `name` is empty, longer than 64 characters, or holds anything but
/// letters, digits, spaces, '-', '_' and '.' (it names a folder of recordings)
void check_trainee_name(const std::string& name);

/// Beside the database: recordings/NAME/TASK_<started, no colons>.lapr, with _2, _3, ... when a
/// session started in the same second has that name already.
[[nodiscard]] std::filesystem::path trainee_recording(const std::filesystem::path& db,
                                                      const std::string& trainee,
                                                      const std::string& task,
                                                      const std::string& started_utc);

/// Files the finished session (`report`: the headless or session report) in the database.
/// @throws InputError naming the database when it is locked, damaged or not ours, and saying
/// where the session's recording and report are kept (they are written before)
void file_session(const TraineeSession& session, const std::filesystem::path& scene,
                  const nlohmann::json& report,
                  const std::optional<std::filesystem::path>& recording,
                  const std::optional<std::filesystem::path>& report_file);

}  // namespace serosa::trainee
