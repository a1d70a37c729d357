// ProgressDb: each trainee's sessions in a local SQLite database (Debian's libsqlite3): when, which
// task, the score and pass of its assessment, its GOALS domains, and where its recording and report
// are. `serosa run --trainee NAME` and `serosa headless --trainee NAME` add to it; `serosa trainee
// NAME` reads it (app/trainee_progress.h).
//
// Schema (PRAGMA user_version 1): trainee(id, name UNIQUE); session(id, trainee_id, task, scene,
// started_utc, simulated_s, score, passed, domains (JSON text), recording, report). A database
// that is locked by another program past a short wait, damaged, or not Serosa's is an InputError
// naming the file and what SQLite said; the caller has written the session's recording and report
// before it asks, so nothing of the session is lost.
#pragma once

#include <filesystem>
#include <optional>
#include <string>
#include <vector>

struct sqlite3;

namespace serosa::app {

struct SessionRecord {
  std::string trainee;
  std::string task;         ///< what was practised: the scene file's name without extension
  std::string scene;        ///< the scene file
  std::string started_utc;  ///< ISO 8601, "2026-12-03T14:25:00Z"
  double simulated_s = 0.0;
  std::optional<double> score;  ///< 0-100; none when the scene scores nothing
  std::optional<bool> passed;
  std::string domains_json;  ///< {"efficiency": 4, ...}; "{}" when none
  std::string recording;     ///< the session's .lapr; empty when not recorded
  std::string report;        ///< its JSON report; empty when none was written
};

/// The default database: $SEROSA_PROGRESS_DB, else $XDG_DATA_HOME/serosa/progress.sqlite, else
/// ~/.local/share/serosa/progress.sqlite.
[[nodiscard]] std::filesystem::path default_progress_db();

class ProgressDb {
 public:
  /// Opens (creating it and its folder when missing) the database at `file`.
  /// @throws InputError naming the file when it cannot be opened, is locked, damaged or not ours
  explicit ProgressDb(const std::filesystem::path& file);
  ~ProgressDb();
  ProgressDb(const ProgressDb&) = delete;
  ProgressDb& operator=(const ProgressDb&) = delete;

  /// Adds one session (and its trainee, the first time), in one transaction.
  void add(const SessionRecord& s);
  /// The trainee's sessions, oldest first (none for an unknown trainee).
  [[nodiscard]] std::vector<SessionRecord> sessions(const std::string& trainee);
  /// Every trainee's name, sorted.
  [[nodiscard]] std::vector<std::string> trainees();

 private:
  void exec(const char* sql);
  [[noreturn]] void fail(const std::string& doing) const;

  std::filesystem::path m_file;
  sqlite3* m_db = nullptr;
};

}  // namespace serosa::app
