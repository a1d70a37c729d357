#include "trainee/progress_db.h"

#include <sqlite3.h>

#include <algorithm>
#include <cstdlib>
#include <fstream>
#include <nlohmann/json.hpp>

#include "engine/input_error.h"

namespace serosa::trainee {

namespace {

constexpr int kSchemaVersion = 2;
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
  report TEXT NOT NULL,
  pass_score REAL,
  failed TEXT,
  below_threshold TEXT);
CREATE INDEX IF NOT EXISTS session_by_trainee ON session(trainee_id, id);
)";

// Version 2's columns, added to a version 1 database (NULL until its reports are read).
const char* const kUpgradeFrom1 = R"(
ALTER TABLE session ADD COLUMN pass_score REAL;
ALTER TABLE session ADD COLUMN failed TEXT;
ALTER TABLE session ADD COLUMN below_threshold TEXT;
)";

const char* const kColumns =
    "t.name, s.task, s.scene, s.started_utc, s.simulated_s, s.score, s.passed, s.domains, "
    "s.recording, s.report, s.pass_score, s.failed, s.below_threshold";

const std::vector<std::string> kSessionColumns{
    "id",     "trainee_id", "task",      "scene",  "started_utc", "simulated_s", "score",
    "passed", "domains",    "recording", "report", "pass_score",  "failed",      "below_threshold"};

const char* const kExpected =
    "a progress database that `serosa headless` or `serosa run` with --trainee NAME wrote "
    "(SQLite, schema version 1 or 2)";

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
  [[nodiscard]] bool null(int i) { return sqlite3_column_type(s_, i) == SQLITE_NULL; }
  [[nodiscard]] std::optional<double> column_real(int i) {
    if (null(i)) return std::nullopt;
    return sqlite3_column_double(s_, i);
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

std::string json_list(const std::vector<std::string>& v) { return nlohmann::json(v).dump(); }

// A JSON array of text as the database keeps it; none when it is not one.
std::optional<std::vector<std::string>> read_list(const std::string& text) {
  const nlohmann::json j = nlohmann::json::parse(text, nullptr, false);
  if (!j.is_array()) return std::nullopt;
  std::vector<std::string> out;
  for (const nlohmann::json& e : j)
    if (e.is_string()) out.push_back(e.get<std::string>());
  return out;
}

std::vector<std::string> strings(const nlohmann::json& a, const char* key) {
  std::vector<std::string> out;
  if (const auto it = a.find(key); it != a.end() && it->is_array())
    for (const nlohmann::json& e : *it)
      if (e.is_string()) out.push_back(e.get<std::string>());
  return out;
}

// The `assessment` of the report at `file`; none when the file has gone or holds no assessment.
std::optional<nlohmann::json> report_assessment(const std::string& file) {
  std::ifstream in(file);
  if (file.empty() || !in) return std::nullopt;
  const nlohmann::json r = nlohmann::json::parse(in, nullptr, false);
  if (!r.is_object() || !r.contains("assessment") || !r["assessment"].is_object())
    return std::nullopt;
  return r["assessment"];
}

}  // namespace

void set_assessment(SessionRecord& r, const nlohmann::json& a) {
  if (const auto it = a.find("score"); it != a.end() && it->is_number())
    r.score = it->get<double>();
  if (const auto it = a.find("passed"); it != a.end() && it->is_boolean())
    r.passed = it->get<bool>();
  if (const auto it = a.find("pass_score"); it != a.end() && it->is_number())
    r.pass_score = it->get<double>();
  if (const auto it = a.find("domains"); it != a.end() && it->is_object())
    r.domains_json = it->dump();
  r.failed = strings(a, "failed");
  r.below_threshold = strings(a, "below_threshold");
  r.reasons_known = true;
}

std::filesystem::path default_progress_db() {
  if (const std::string f = env("SEROSA_PROGRESS_DB"); !f.empty()) return f;
  if (const std::string x = env("XDG_DATA_HOME"); !x.empty())
    return std::filesystem::path(x) / "serosa" / "progress.sqlite";
  return std::filesystem::path(env("HOME")) / ".local" / "share" / "serosa" / "progress.sqlite";
}

ProgressDb::ProgressDb(const std::filesystem::path& file, Open mode) : m_file(file) {
  std::error_code ec;
  if (mode == Open::existing && !std::filesystem::exists(file, ec))
    throw InputError(file.string(), 0, "no progress database here", kExpected);
  if (mode == Open::create && file.has_parent_path())
    std::filesystem::create_directories(file.parent_path(), ec);
  const int flags = SQLITE_OPEN_READWRITE | (mode == Open::create ? SQLITE_OPEN_CREATE : 0);
  if (sqlite3_open_v2(file.c_str(), &m_db, flags, nullptr) != SQLITE_OK) {
    const std::string why = m_db != nullptr ? sqlite3_errmsg(m_db) : "out of memory";
    sqlite3_close(m_db);
    m_db = nullptr;
    throw InputError(file.string(), 0, std::string("cannot open the progress database: ") + why,
                     "a writable path for a SQLite file");
  }
  sqlite3_busy_timeout(m_db, kBusyWaitMs);
  try {
    prepare_schema(mode);
  } catch (...) {
    sqlite3_close(m_db);
    m_db = nullptr;
    throw;
  }
}

ProgressDb::~ProgressDb() { sqlite3_close(m_db); }

void ProgressDb::prepare_schema(Open mode) {
  // One transaction: what is read and what is created are consistent with any other session
  // creating or upgrading the same database at once.
  exec(mode == Open::create ? "BEGIN IMMEDIATE" : "BEGIN", "opening it");
  try {
    const int version = check_kind(mode);
    if (version == 0) {
      exec(kSchema);
      exec("PRAGMA user_version = 2");
    }
    exec("COMMIT");
    if (version == 1) upgrade_from_version_1();
    check_columns();
  } catch (...) {
    sqlite3_exec(m_db, "ROLLBACK", nullptr, nullptr, nullptr);
    throw;
  }
}

int ProgressDb::check_kind(Open mode) {
  const int version = user_version();
  const std::vector<std::string> tables = table_names();
  const auto has = [&](const char* t) {
    return std::find(tables.begin(), tables.end(), t) != tables.end();
  };
  if (version == 0 && tables.empty()) {
    if (mode == Open::existing) not_ours("an empty database: no session was ever filed in it");
    return 0;
  }
  if (version == 0 || !has("trainee") || !has("session")) {
    std::string listed;
    for (const std::string& t : tables) listed.append(listed.empty() ? "" : ", ").append(t);
    not_ours(std::string("another program's SQLite database (user_version ") +
             std::to_string(version) + ", tables: " + listed + ")");
  }
  if (version > kSchemaVersion)
    throw InputError(
        m_file.string(), 0,
        std::string("written by a newer Serosa (schema version ") + std::to_string(version) + ")",
        "schema version 1 or 2; read it with the Serosa that wrote it");
  return version;
}

int ProgressDb::user_version() {
  Statement v(m_db, "PRAGMA user_version");
  if (!v.ok() || sqlite3_step(v.get()) != SQLITE_ROW) fail("reading its version");
  return sqlite3_column_int(v.get(), 0);
}

std::vector<std::string> ProgressDb::table_names() {
  Statement q(m_db,
              "SELECT name FROM sqlite_master WHERE type = 'table' AND name NOT LIKE "
              "'sqlite_%' ORDER BY name");
  if (!q.ok()) fail("reading its tables");
  std::vector<std::string> out;
  while (sqlite3_step(q.get()) == SQLITE_ROW) out.push_back(q.column_text(0));
  return out;
}

void ProgressDb::check_columns() {
  Statement q(m_db, "PRAGMA table_info(session)");
  if (!q.ok()) fail("reading its tables");
  std::vector<std::string> have;
  while (sqlite3_step(q.get()) == SQLITE_ROW) have.push_back(q.column_text(1));
  for (const std::string& c : kSessionColumns)
    if (std::find(have.begin(), have.end(), c) == have.end())
      not_ours(std::string("its session table has no column '") + c + "'");
}

void ProgressDb::upgrade_from_version_1() {
  exec("BEGIN IMMEDIATE", "upgrading it to schema version 2");
  try {
    if (user_version() == 1) {  // not upgraded by another program meanwhile
      exec(kUpgradeFrom1);
      Statement q(m_db, "SELECT id, score, report FROM session");
      Statement u(m_db,
                  "UPDATE session SET pass_score = ?2, failed = ?3, below_threshold = ?4 "
                  "WHERE id = ?1");
      if (!q.ok() || !u.ok()) fail("upgrading it to schema version 2");
      while (sqlite3_step(q.get()) == SQLITE_ROW) {
        SessionRecord r;
        const std::optional<nlohmann::json> a = report_assessment(q.column_text(2));
        if (a) set_assessment(r, *a);
        if (!a && !q.null(1)) continue;  // scored, but its report has gone: reasons unknown
        sqlite3_bind_int64(u.get(), 1, sqlite3_column_int64(q.get(), 0));
        u.real(2, r.pass_score);
        u.text(3, json_list(r.failed));
        u.text(4, json_list(r.below_threshold));
        if (sqlite3_step(u.get()) != SQLITE_DONE) fail("upgrading it to schema version 2");
        sqlite3_reset(u.get());
      }
      exec("PRAGMA user_version = 2");
    }
    exec("COMMIT");
  } catch (...) {
    sqlite3_exec(m_db, "ROLLBACK", nullptr, nullptr, nullptr);
    throw;
  }
}

void ProgressDb::exec(const char* sql, const char* doing) {
  char* err = nullptr;
  if (sqlite3_exec(m_db, sql, nullptr, nullptr, &err) != SQLITE_OK) {
    sqlite3_free(err);
    fail(doing);
  }
}

void ProgressDb::fail(const std::string& doing) const {
  const int code = sqlite3_errcode(m_db);
  std::string why = sqlite3_errmsg(m_db);
  if (code == SQLITE_NOTADB) not_ours(std::string("not a SQLite file (SQLite: ") + why + ")");
  if (code == SQLITE_BUSY || code == SQLITE_LOCKED) why += " by another program";
  throw InputError(m_file.string(), 0, std::string("progress database, ") + doing + ": " + why,
                   "a Serosa progress database (SQLite) that no other program holds locked");
}

void ProgressDb::not_ours(const std::string& why) const {
  throw InputError(m_file.string(), 0, std::string("not a Serosa progress database: ") + why,
                   kExpected);
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
                "passed, domains, recording, report, pass_score, failed, below_threshold) SELECT "
                "id, ?2, ?3, ?4, ?5, ?6, ?7, ?8, ?9, ?10, ?11, ?12, ?13 FROM trainee WHERE name = "
                "?1");
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
    q.real(11, s.pass_score);
    if (s.reasons_known) {
      q.text(12, json_list(s.failed));
      q.text(13, json_list(s.below_threshold));
    }
    if (sqlite3_step(q.get()) != SQLITE_DONE) fail("adding the session");
    exec("COMMIT");
  } catch (...) {
    sqlite3_exec(m_db, "ROLLBACK", nullptr, nullptr, nullptr);
    throw;
  }
}

std::vector<SessionRecord> ProgressDb::select(const std::string& where,
                                              const std::string& trainee) {
  const std::string sql = std::string("SELECT ") + kColumns +
                          " FROM session s JOIN trainee t ON t.id = s.trainee_id " + where +
                          " ORDER BY t.name, s.id";
  Statement q(m_db, sql.c_str());
  if (!q.ok()) fail("reading the sessions");
  if (!where.empty()) q.text(1, trainee);
  std::vector<SessionRecord> out;
  int rc = 0;
  while ((rc = sqlite3_step(q.get())) == SQLITE_ROW) {
    SessionRecord r;
    r.trainee = q.column_text(0);
    r.task = q.column_text(1);
    r.scene = q.column_text(2);
    r.started_utc = q.column_text(3);
    r.simulated_s = sqlite3_column_double(q.get(), 4);
    r.score = q.column_real(5);
    if (!q.null(6)) r.passed = sqlite3_column_int(q.get(), 6) != 0;
    r.domains_json = q.column_text(7);
    r.recording = q.column_text(8);
    r.report = q.column_text(9);
    r.pass_score = q.column_real(10);
    const auto failed = read_list(q.column_text(11));
    const auto below = read_list(q.column_text(12));
    r.reasons_known = failed && below;
    if (failed) r.failed = *failed;
    if (below) r.below_threshold = *below;
    out.push_back(std::move(r));
  }
  if (rc != SQLITE_DONE) fail("reading the sessions");
  return out;
}

std::vector<SessionRecord> ProgressDb::sessions(const std::string& trainee) {
  return select("WHERE t.name = ?1", trainee);
}

std::vector<SessionRecord> ProgressDb::all_sessions() { return select("", ""); }

std::vector<std::string> ProgressDb::trainees() {
  Statement q(m_db, "SELECT name FROM trainee ORDER BY name");
  if (!q.ok()) fail("reading the trainees");
  std::vector<std::string> out;
  int rc = 0;
  while ((rc = sqlite3_step(q.get())) == SQLITE_ROW) out.push_back(q.column_text(0));
  if (rc != SQLITE_DONE) fail("reading the trainees");
  return out;
}

}  // namespace serosa::trainee
