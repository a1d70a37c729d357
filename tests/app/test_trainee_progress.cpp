// The trainees' progress in real SQLite (trainee/progress_db.h): sessions round-trip; the per-task
// progress agrees with an independent count over random histories; `serosa headless --trainee`
// files each session with its recording and report; `serosa trainee` prints the table and draws
// the learning curve (leaving nothing beside it but the picture) and why each session failed; a
// locked, damaged or foreign database is an error naming it and saying where the session is kept,
// and the recording is complete.
#include <gtest/gtest.h>
#include <sqlite3.h>

#include <fstream>
#include <map>
#include <random>
#include <string>

#include "app_test_util.h"
#include "engine/input_error.h"
#include "recording/recording_reader.h"
#include "trainee/progress_db.h"
#include "trainee/trainee_progress.h"

namespace serosa::app {
namespace {

using namespace serosa::trainee;

using namespace serosa::app::testing;

SessionRecord record(const std::string& trainee, const std::string& task, int i,
                     std::optional<double> score, std::optional<bool> passed) {
  SessionRecord r;
  r.trainee = trainee;
  r.task = task;
  r.scene = "/scenes/" + task + ".toml";
  r.started_utc = "2026-12-03T10:00:" + std::string(i < 10 ? "0" : "") + std::to_string(i) + "Z";
  r.simulated_s = 0.5 * i;
  r.score = score;
  r.passed = passed;
  r.domains_json = score ? "{\"efficiency\":4}" : "{}";
  r.recording = "/rec/" + std::to_string(i) + ".lapr";
  r.report = i % 2 == 0 ? "/rec/" + std::to_string(i) + ".json" : "";
  return r;
}

TEST(ProgressDb, SessionsRoundTripPerTraineeInOrder) {
  const fs::path dir = out_dir("progress_roundtrip");
  const fs::path file = dir / "sub" / "p.sqlite";  // its folder is made
  {
    ProgressDb db(file);
    db.add(record("ann", "appendectomy", 1, 77.5, false));
    db.add(record("bo", "appendectomy", 2, std::nullopt, std::nullopt));
    db.add(record("ann", "cutting_line", 3, 91.0, true));
  }
  ProgressDb db(file);  // reopened: the schema is there already
  EXPECT_EQ(db.trainees(), (std::vector<std::string>{"ann", "bo"}));
  const auto ann = db.sessions("ann");
  ASSERT_EQ(ann.size(), 2u);
  const SessionRecord want = record("ann", "cutting_line", 3, 91.0, true);
  const SessionRecord& got = ann[1];
  EXPECT_EQ(got.task, want.task);
  EXPECT_EQ(got.scene, want.scene);
  EXPECT_EQ(got.started_utc, want.started_utc);
  EXPECT_EQ(got.simulated_s, want.simulated_s);
  EXPECT_EQ(got.score, want.score);
  EXPECT_EQ(got.passed, want.passed);
  EXPECT_EQ(got.domains_json, want.domains_json);
  EXPECT_EQ(got.recording, want.recording);
  EXPECT_EQ(got.report, want.report);
  EXPECT_EQ(ann[0].score, 77.5);
  const auto bo = db.sessions("bo");
  ASSERT_EQ(bo.size(), 1u);
  EXPECT_FALSE(bo[0].score.has_value());
  EXPECT_FALSE(bo[0].passed.has_value());
  EXPECT_TRUE(db.sessions("nobody").empty());
}

TEST(ProgressDb, TaskProgressAgreesWithAnIndependentCountOverRandomHistories) {
  std::mt19937 rng(9);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  const fs::path dir = out_dir("progress_random");
  ProgressDb db(dir / "p.sqlite");
  for (int trial = 0; trial < 40; ++trial) {
    std::string who = "trainee_";
    who += std::to_string(trial);
    const int n = 1 + static_cast<int>(25 * u(rng));
    std::map<std::string, std::vector<std::pair<double, bool>>> by_task;
    for (int i = 0; i < n; ++i) {
      const std::string task = u(rng) < 0.5 ? "a" : (u(rng) < 0.5 ? "b" : "c");
      const double score = 100.0 * u(rng);
      const bool passed = score > 70.0 && u(rng) < 0.8;
      db.add(record(who, task, i, score, passed));
      by_task[task].emplace_back(score, passed);
    }
    const auto progress = task_progress(db.sessions(who));
    ASSERT_EQ(progress.size(), by_task.size());
    for (const TaskProgress& p : progress) {
      const auto& h = by_task.at(p.task);
      EXPECT_EQ(p.sessions, static_cast<int>(h.size()));
      double best = 0.0;
      int passed = 0;
      std::optional<int> first;
      for (std::size_t k = 0; k < h.size(); ++k) {
        best = std::max(best, h[k].first);
        if (h[k].second) {
          ++passed;
          if (!first) first = static_cast<int>(k) + 1;
        }
      }
      EXPECT_EQ(p.best, best);
      EXPECT_EQ(p.last, h.back().first);
      EXPECT_EQ(p.passed, passed);
      EXPECT_EQ(p.first_passed, first);
    }
  }
}

std::string headless_for(const std::string& trainee, const fs::path& db, int steps = 60) {
  return "headless '" + source("config/transection.toml").string() + "' --steps " +
         std::to_string(steps) + " --trainee '" + trainee + "' --db '" + db.string() + "'";
}

// The file named after "kept: recording " in an error message.
fs::path kept_recording(const std::string& out) {
  const std::string key = "kept: recording ";
  const auto at = out.find(key);
  if (at == std::string::npos) return {};
  const auto end = out.find(", report", at);
  return out.substr(at + key.size(), end - at - key.size());
}

TEST(ProgressDb, HeadlessFilesTheSessionAndTraineePrintsAndPlotsIt) {
  const fs::path dir = out_dir("progress_cli");
  const fs::path db = dir / "p.sqlite";
  for (int i = 0; i < 2; ++i) {
    const CliResult r = run_serosa(headless_for("Dr. Ann", db));
    ASSERT_EQ(r.code, 0) << r.out;
  }
  const auto sessions = ProgressDb(db).sessions("Dr. Ann");
  ASSERT_EQ(sessions.size(), 2u);
  EXPECT_NE(sessions[0].recording, sessions[1].recording);  // even within the same second
  EXPECT_NE(sessions[0].report, sessions[1].report);
  for (const SessionRecord& s : sessions) {
    EXPECT_EQ(s.task, "transection");
    ASSERT_TRUE(s.score.has_value());  // the default scene scores its sessions
    EXPECT_FALSE(*s.passed);           // 60 steps: nothing transected yet
    EXPECT_TRUE(recording::read_recording(s.recording).complete) << s.recording;
    EXPECT_TRUE(fs::exists(s.report)) << s.report;
  }
  const fs::path png = dir / "curve.png";
  const CliResult t =
      run_serosa("trainee 'Dr. Ann' --db '" + db.string() + "' --plot '" + png.string() + "'");
  ASSERT_EQ(t.code, 0) << t.out;
  EXPECT_NE(t.out.find("trainee Dr. Ann: 2 sessions"), std::string::npos) << t.out;
  EXPECT_NE(t.out.find("transection                  2       0"), std::string::npos) << t.out;
  EXPECT_NE(t.out.find("not yet"), std::string::npos) << t.out;
  EXPECT_GT(fs::file_size(png), 1000u);
  // Nothing but the picture is left: gnuplot's script and data went to a folder now removed.
  for (const auto& entry : fs::directory_iterator(dir))
    EXPECT_TRUE(entry.path().extension() != ".dat" && entry.path().extension() != ".gp")
        << entry.path();
  EXPECT_NE(t.out.find("pass at"), std::string::npos) << t.out;
  EXPECT_NE(t.out.find("     failed: pieces.appendix = 1 < 2\n"), std::string::npos) << t.out;

  const CliResult unknown = run_serosa("trainee zed --db '" + db.string() + "'");
  EXPECT_EQ(unknown.code, 1) << unknown.out;
  EXPECT_NE(unknown.out.find("no sessions of trainee 'zed'"), std::string::npos) << unknown.out;
  EXPECT_NE(unknown.out.find("Dr. Ann"), std::string::npos) << unknown.out;
  const CliResult bad = run_serosa(headless_for("../x", db));
  EXPECT_EQ(bad.code, 1) << bad.out;
  EXPECT_NE(bad.out.find("is not a trainee's name"), std::string::npos) << bad.out;
}

TEST(ProgressDb, ALockedDatabaseIsAnErrorAndTheSessionIsKept) {
  const fs::path dir = out_dir("progress_locked");
  const fs::path db = dir / "p.sqlite";
  { ProgressDb create(db); }
  sqlite3* other = nullptr;
  ASSERT_EQ(sqlite3_open(db.c_str(), &other), SQLITE_OK);
  ASSERT_EQ(sqlite3_exec(other, "BEGIN EXCLUSIVE", nullptr, nullptr, nullptr), SQLITE_OK);
  const CliResult r = run_serosa(headless_for("cy", db));
  sqlite3_exec(other, "ROLLBACK", nullptr, nullptr, nullptr);
  sqlite3_close(other);
  EXPECT_EQ(r.code, 1) << r.out;
  EXPECT_NE(r.out.find(db.string()), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("locked"), std::string::npos) << r.out;
  const fs::path rec = kept_recording(r.out);
  ASSERT_FALSE(rec.empty()) << r.out;
  EXPECT_TRUE(recording::read_recording(rec).complete) << rec;
  // Unlocked, the next session is filed (the one refused is not).
  const CliResult again = run_serosa(headless_for("cy", db));
  ASSERT_EQ(again.code, 0) << again.out;
  EXPECT_EQ(ProgressDb(db).sessions("cy").size(), 1u);
}

TEST(ProgressDb, ADamagedOrForeignDatabaseIsAnErrorAndTheSessionIsKept) {
  const fs::path dir = out_dir("progress_damaged");
  const fs::path damaged = dir / "damaged.sqlite";
  std::ofstream(damaged) << std::string(4096, 'x');
  const CliResult r = run_serosa(headless_for("di", damaged));
  EXPECT_EQ(r.code, 1) << r.out;
  EXPECT_NE(r.out.find("not a database"), std::string::npos) << r.out;
  EXPECT_TRUE(recording::read_recording(kept_recording(r.out)).complete) << r.out;

  const fs::path foreign = dir / "foreign.sqlite";
  sqlite3* f = nullptr;
  ASSERT_EQ(sqlite3_open(foreign.c_str(), &f), SQLITE_OK);
  sqlite3_exec(f, "CREATE TABLE x(y); PRAGMA user_version = 7", nullptr, nullptr, nullptr);
  sqlite3_close(f);
  try {
    ProgressDb db(foreign);
    ADD_FAILURE() << "opened a foreign database";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("not a Serosa progress database"), std::string::npos)
        << e.what();
  }
}

}  // namespace
}  // namespace serosa::app
