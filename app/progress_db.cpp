#include "app/progress_db.h"

#include <sqlite3.h>

#include <cstdlib>

#include "engine/input_error.h"

namespace serosa::app {

namespace {

constexpr int kSchemaVersion = 1;
constexpr int kBusyWaitMs = 2000;  // another session finishing its write takes milliseconds

const char* const kSchema = R"(
CREATE TABLE IF NOT EXISTS trainee (
  id INTEGER PRIMARY KEY,
  name TEXT NOT NULL UNIQUE);
CREATE TABLE IF NOT EXISTS session (
  id INTEGER PRIMARY KEY,
  trainee_id INTEGER NOT NULL REFERENCES trainee(id),
  task TEXT NOT NULL,
  scene TEXT NOT NULL,
  started_utc TEXT NOT NULL,
  simulated_s REAL NOT NULL,
  score REAL,
  passed INTEGER,
  domains TEXT NOT NULL,
  recording TEXT NOT NULL,
  report TEXT NOT NULL);
CREATE INDEX IF NOT EXISTS session_by_trainee ON session(trainee_id, id);
)";

// A prepared statement, finalized when it goes.
class Statement {
 public:
  Statement(sqlite3* db, const char* sql) {
    ok_ = sqlite3_prepare_v2(db, sql, -1, &s_, nullptr) == SQLITE_OK;
  }
  ~Statement() { sqlite3_finalize(s_); }
  Statement(const Statement&) = delete;
  Statement& operator=(const Statement&) = delete;
  [[nodiscard]] bool ok() const { return ok_; }
  sqlite3_stmt* get() { return s_; }
  void text(int i, const std::string& v) {
    sqlite3_bind_text(s_, i, v.c_str(), static_cast<int>(v.size()), SQLITE_TRANSIENT);
  }
  void real(int i, std::optional<double> v) {
    if (v)
      sqlite3_bind_double(s_, i, *v);
    else
      sqlite3_bind_null(s_, i);
  }
  [[nodiscard]] std::string column_text(int i) {
    const unsigned char* t = sqlite3_column_text(s_, i);
    return t != nullptr ? reinterpret_cast<const char*>(t) : "";
  }

 private:
  sqlite3_stmt* s_ = nullptr;
  bool ok_ = false;
};

std::string env(const char* name) {
  const char* v = std::getenv(name);
  return v != nullptr ? v : "";
}

}  // namespace

std::filesystem::path default_progress_db() {
  if (const std::string f = env("SEROSA_PROGRESS_DB"); !f.empty()) return f;
  if (const std::string x = env("XDG_DATA_HOME"); !x.empty())
    return std::filesystem::path(x) / "serosa" / "progress.sqlite";
  return std::filesystem::path(env("HOME")) / ".local" / "share" / "serosa" / "progress.sqlite";
}

ProgressDb::ProgressDb(const std::filesystem::path& file) : m_file(file) {
  std::error_code ec;
  if (file.has_parent_path()) std::filesystem::create_directories(file.parent_path(), ec);
  if (sqlite3_open_v2(file.c_str(), &m_db, SQLITE_OPEN_READWRITE | SQLITE_OPEN_CREATE, nullptr) !=
      SQLITE_OK) {
    const std::string why = m_db != nullptr ? sqlite3_errmsg(m_db) : "out of memory";
    sqlite3_close(m_db);
    m_db = nullptr;
    throw InputError(file.string(), 0, "cannot open the progress database: " + why,
                     "a writable path for a SQLite file");
  }
  sqlite3_busy_timeout(m_db, kBusyWaitMs);
  try {
    Statement v(m_db, "PRAGMA user_version");
    if (!v.ok() || sqlite3_step(v.get()) != SQLITE_ROW) fail("reading its version");
    const int version = sqlite3_column_int(v.get(), 0);
    if (version != 0 && version != kSchemaVersion)
      throw InputError(
          file.string(), 0,
          "not a Serosa progress database (user_version " + std::to_string(version) + ")",
          "a progress database of schema version 1");
    exec("BEGIN IMMEDIATE");
    exec(kSchema);
    exec("PRAGMA user_version = 1");
    exec("COMMIT");
  } catch (...) {
    sqlite3_close(m_db);
    m_db = nullptr;
    throw;
  }
}

ProgressDb::~ProgressDb() { sqlite3_close(m_db); }

void ProgressDb::exec(const char* sql) {
  char* err = nullptr;
  if (sqlite3_exec(m_db, sql, nullptr, nullptr, &err) != SQLITE_OK) {
    sqlite3_free(err);
    fail("writing to it");
  }
}

void ProgressDb::fail(const std::string& doing) const {
  const int code = sqlite3_errcode(m_db);
  std::string why = sqlite3_errmsg(m_db);
  if (code == SQLITE_BUSY || code == SQLITE_LOCKED) why += " by another program";
  throw InputError(m_file.string(), 0, "progress database, " + doing + ": " + why,
                   "a Serosa progress database (SQLite) that no other program holds locked");
}

void ProgressDb::add(const SessionRecord& s) {
  exec("BEGIN IMMEDIATE");
  try {
    Statement t(m_db, "INSERT OR IGNORE INTO trainee(name) VALUES(?1)");
    if (!t.ok()) fail("adding the trainee");
    t.text(1, s.trainee);
    if (sqlite3_step(t.get()) != SQLITE_DONE) fail("adding the trainee");
    Statement q(m_db,
                "INSERT INTO session(trainee_id, task, scene, started_utc, simulated_s, score, "
                "passed, domains, recording, report) SELECT id, ?2, ?3, ?4, ?5, ?6, ?7, ?8, ?9, "
                "?10 FROM trainee WHERE name = ?1");
    if (!q.ok()) fail("adding the session");
    q.text(1, s.trainee);
    q.text(2, s.task);
    q.text(3, s.scene);
    q.text(4, s.started_utc);
    q.real(5, s.simulated_s);
    q.real(6, s.score);
    if (s.passed)
      sqlite3_bind_int(q.get(), 7, *s.passed ? 1 : 0);
    else
      sqlite3_bind_null(q.get(), 7);
    q.text(8, s.domains_json.empty() ? "{}" : s.domains_json);
    q.text(9, s.recording);
    q.text(10, s.report);
    if (sqlite3_step(q.get()) != SQLITE_DONE) fail("adding the session");
    exec("COMMIT");
  } catch (...) {
    sqlite3_exec(m_db, "ROLLBACK", nullptr, nullptr, nullptr);
    throw;
  }
}

std::vector<SessionRecord> ProgressDb::sessions(const std::string& trainee) {
  Statement q(m_db,
              "SELECT t.name, s.task, s.scene, s.started_utc, s.simulated_s, s.score, s.passed, "
              "s.domains, s.recording, s.report FROM session s JOIN trainee t ON t.id = "
              "s.trainee_id WHERE t.name = ?1 ORDER BY s.id");
  if (!q.ok()) fail("reading the sessions");
  q.text(1, trainee);
  std::vector<SessionRecord> out;
  int rc = 0;
  while ((rc = sqlite3_step(q.get())) == SQLITE_ROW) {
    SessionRecord r;
    r.trainee = q.column_text(0);
    r.task = q.column_text(1);
    r.scene = q.column_text(2);
    r.started_utc = q.column_text(3);
    r.simulated_s = sqlite3_column_double(q.get(), 4);
    if (sqlite3_column_type(q.get(), 5) != SQLITE_NULL) r.score = sqlite3_column_double(q.get(), 5);
    if (sqlite3_column_type(q.get(), 6) != SQLITE_NULL)
      r.passed = sqlite3_column_int(q.get(), 6) != 0;
    r.domains_json = q.column_text(7);
    r.recording = q.column_text(8);
    r.report = q.column_text(9);
    out.push_back(std::move(r));
  }
  if (rc != SQLITE_DONE) fail("reading the sessions");
  return out;
}

std::vector<std::string> ProgressDb::trainees() {
  Statement q(m_db, "SELECT name FROM trainee ORDER BY name");
  if (!q.ok()) fail("reading the trainees");
  std::vector<std::string> out;
  int rc = 0;
  while ((rc = sqlite3_step(q.get())) == SQLITE_ROW) out.push_back(q.column_text(0));
  if (rc != SQLITE_DONE) fail("reading the trainees");
  return out;
}

}  // namespace serosa::app
