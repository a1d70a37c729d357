// ProgressDb: each trainee's sessions in a local SQLite database (Debian's libsqlite3): when, which
// task, the score and pass of its assessment, why it failed, its GOALS domains, and where its
// recording and report are. `serosa run --trainee NAME` and `serosa headless --trainee NAME` add
// to it; `serosa trainee` and `serosa cohort` read it (trainee/trainee_progress.h,
// trainee/cohort.h).
//
// Schema (PRAGMA user_version 2): trainee(id, name UNIQUE); session(id, trainee_id, task, scene,
// started_utc, simulated_s, score, passed, domains (JSON text), recording, report, pass_score,
// failed, below_threshold (JSON arrays of text; NULL: not known)). Version 2 keeps why a session
// failed in the database itself, because reports get moved or deleted; a version 1 database is
// upgraded when opened, reading each session's reasons from its report while it is still there.
// A database that is locked by another program past a short wait, damaged, not SQLite, another
// program's SQLite or a newer Serosa's is an InputError naming the file and what was expected;
// the caller has written the session's recording and report before it asks, so nothing of the
// session is lost.
#pragma once

#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include <nlohmann/json_fwd.hpp>

struct sqlite3;

namespace serosa::trainee {

struct SessionRecord {
  std::string trainee;
  std::string task;         ///< the task's name as `serosa tasks` says it, else the scene's stem
  std::string scene;        ///< the scene file
  std::string started_utc;  ///< ISO 8601, "2026-12-03T14:25:00Z"
  double simulated_s = 0.0;
  std::optional<double> score;  ///< 0-100; none when the scene scores nothing
  std::optional<bool> passed;
  std::string domains_json;                  ///< {"efficiency": 4, ...}; "{}" when none
  std::string recording;                     ///< the session's .lapr; empty when not recorded
  std::string report;                        ///< its JSON report; empty when none was written
  std::optional<double> pass_score;          ///< the rubric's pass score when it was scored
  std::vector<std::string> failed;           ///< the assessment's `failed`: why it did not pass
  std::vector<std::string> below_threshold;  ///< every metric on the wrong side of its limit
  bool reasons_known = true;  ///< false: upgraded from version 1 after its report had gone
};

/// Fills score, pass, domains, pass score and the reasons from a report's `assessment` object.
void set_assessment(SessionRecord& r, const nlohmann::json& assessment);

/// The default database: $SEROSA_PROGRESS_DB, else $XDG_DATA_HOME/serosa/progress.sqlite, else
/// ~/.local/share/serosa/progress.sqlite.
[[nodiscard]] std::filesystem::path default_progress_db();

class ProgressDb {
 public:
  /// create: a session is being filed (the file and its folder are made when missing);
  /// existing: progress is being read, and a missing or empty file is an error.
  enum class Open { create, existing };

  /// Opens the database at `file`, upgrading a version 1 database.
  /// @throws InputError naming the file when it is missing (Open::existing), cannot be opened, is
  /// locked, damaged, not SQLite, another program's or a newer Serosa's
  explicit ProgressDb(const std::filesystem::path& file, Open mode = Open::create);
  ~ProgressDb();
  ProgressDb(const ProgressDb&) = delete;
  ProgressDb& operator=(const ProgressDb&) = delete;

  /// Adds one session (and its trainee, the first time), in one transaction.
  void add(const SessionRecord& s);
  /// The trainee's sessions, oldest first (none for an unknown trainee).
  [[nodiscard]] std::vector<SessionRecord> sessions(const std::string& trainee);
  /// Every trainee's sessions: by name, each trainee's oldest first.
  [[nodiscard]] std::vector<SessionRecord> all_sessions();
  /// Every trainee's name, sorted.
  [[nodiscard]] std::vector<std::string> trainees();

 private:
  void prepare_schema(Open mode);
  [[nodiscard]] int check_kind(Open mode);
  [[nodiscard]] int user_version();
  void upgrade_from_version_1();
  void check_columns();
  [[nodiscard]] std::vector<std::string> table_names();
  [[nodiscard]] std::vector<SessionRecord> select(const std::string& where,
                                                  const std::string& trainee);
  void exec(const char* sql, const char* doing = "writing to it");
  [[noreturn]] void fail(const std::string& doing) const;
  [[noreturn]] void not_ours(const std::string& why) const;

  std::filesystem::path m_file;
  sqlite3* m_db = nullptr;
};

}  // namespace serosa::trainee
