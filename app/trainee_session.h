// Keeping a trainee's session: where it is recorded when no --record is given, and filing it in
// the progress database once its recording and report are written (app/progress_db.h).
#pragma once

#include <filesystem>
#include <optional>
#include <string>

#include <nlohmann/json.hpp>

namespace serosa::app {

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

/// Files the finished session (`report`: the headless or session report) for `trainee` in `db`.
/// @throws InputError naming the database when it is locked, damaged or not ours, and saying
/// where the session's recording and report are kept (they are written before)
void file_session(const std::filesystem::path& db, const std::string& trainee,
                  const std::filesystem::path& scene, const std::string& started_utc,
                  const nlohmann::json& report,
                  const std::optional<std::filesystem::path>& recording,
                  const std::optional<std::filesystem::path>& report_file);

}  // namespace serosa::app
