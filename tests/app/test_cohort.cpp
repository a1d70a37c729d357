// The cohort (trainee/cohort.h, trainee/cohort_csv.h, trainee/cohort_html.h) from hand-made
// sessions and databases, fast: the trainee x task table, the pass rates and the criteria counted;
// task names as the task list says them; the CSV quoted; every text on the page escaped and nothing
// on it fetched; links relative where they can be. Bad input: a missing, foreign or non-SQLite
// database is a clear error (exit 1); a moved recording is a warning and shows as missing on the
// page, which is written all the same. A version 1 database is upgraded with the reasons its
// reports still hold. The whole path through headless runs and a browser: test_cohort_browser.cpp.
#include <gtest/gtest.h>
#include <sqlite3.h>

#include <algorithm>
#include <fstream>
#include <string>

#include "app_test_util.h"
#include "engine/input_error.h"
#include "trainee/cohort.h"
#include "trainee/cohort_csv.h"
#include "trainee/cohort_html.h"
#include "trainee/cohort_markup.h"
#include "trainee/progress_db.h"
#include "trainee/task_names.h"

namespace serosa::app {
namespace {

using namespace serosa::trainee;

using namespace serosa::app::testing;

SessionRecord session(const std::string& trainee, const std::string& scene_stem, int minute,
                      std::optional<double> score, std::vector<std::string> failed = {},
                      std::vector<std::string> below = {}) {
  SessionRecord r;
  r.trainee = trainee;
  r.task = scene_stem;  // as a version 1 database filed it
  r.scene = "/elsewhere/config/" + scene_stem + ".toml";
  r.started_utc =
      "2026-12-03T10:" + std::string(minute < 10 ? "0" : "") + std::to_string(minute) + ":00Z";
  r.score = score;
  if (score) {
    r.pass_score = 80.0;
    r.passed = failed.empty();
  }
  r.failed = std::move(failed);
  r.below_threshold = std::move(below);
  return r;
}

TaskNames shipped_names() { return TaskNames(load_tasks(source("config/tasks.toml"))); }

const std::string kUnder = "score 52 under the pass score of 80";
const std::string kPlaced = "transfer.placed = 0, below the limit of 1 (critical)";
const std::string kDrops = "transfer.drops = 2, above the limit of 0";

std::vector<SessionRecord> three_trainees() {
  return {session("bo", "transfer", 1, 46.0, {kUnder, kPlaced}, {kPlaced, kDrops}),
          session("bo", "transfer", 2, 97.0),
          session("ann", "cut_line", 3, 90.0),
          session("ann", "camera", 4, 52.0, {kUnder}, {}),
          session("ann", "camera", 5, 100.0),
          session("cy", "transfer", 6, 40.0, {kUnder, kPlaced}, {kPlaced}),
          session("cy", "my_own_scene", 7, std::nullopt)};
}

TEST(Cohort, GathersEveryTraineeAndTaskInTheCurriculumsOrder) {
  const Cohort c = gather_cohort(three_trainees(), shipped_names());
  // cut_line.toml is the task "cut-line"; a scene that is no task keeps its stem, after them.
  EXPECT_EQ(c.tasks, (std::vector<std::string>{"camera", "transfer", "cut-line", "my_own_scene"}));
  ASSERT_EQ(c.trainees.size(), 3u);
  EXPECT_EQ(c.trainees[0].name, "ann");
  EXPECT_EQ(c.sessions, 7);
  const TaskProgress* camera = c.trainees[0].on("camera");
  ASSERT_NE(camera, nullptr);
  EXPECT_EQ(camera->sessions, 2);
  EXPECT_EQ(camera->best, 100.0);
  EXPECT_EQ(camera->last, 100.0);
  EXPECT_EQ(camera->passed, 1);
  EXPECT_TRUE(camera->last_passed);
  EXPECT_EQ(c.trainees[0].on("transfer"), nullptr);
  // The trainee's own tasks come in the curriculum's order too.
  EXPECT_EQ(c.trainees[0].tasks[0].task, "camera");
  EXPECT_EQ(c.trainees[0].tasks[1].task, "cut-line");
  const TaskProgress* cy = c.trainees[2].on("transfer");
  ASSERT_NE(cy, nullptr);
  EXPECT_FALSE(cy->last_passed);
  EXPECT_EQ(cy->passed, 0);

  ASSERT_EQ(c.pass_rates.size(), 4u);
  const TaskPassRate& transfer = c.pass_rates[1];
  EXPECT_EQ(transfer.task, "transfer");
  EXPECT_EQ(transfer.trainees, 2);
  EXPECT_EQ(transfer.trainees_passed, 1);
  EXPECT_EQ(transfer.sessions, 3);
  EXPECT_EQ(transfer.sessions_passed, 1);
  EXPECT_EQ(transfer.pass_score, 80.0);
}

TEST(Cohort, CountsEachMissedCriterionOncePerSession) {
  const Cohort c = gather_cohort(three_trainees(), shipped_names());
  ASSERT_GE(c.criteria.size(), 3u);
  // The score under the pass score: three sessions; transfer.placed is on both lists of two
  // sessions and counts once in each.
  EXPECT_EQ(c.criteria[0].criterion, "score under the pass score");
  EXPECT_EQ(c.criteria[0].sessions, 3);
  EXPECT_EQ(c.criteria[0].failing, 3);
  EXPECT_EQ(c.criteria[0].tasks, (std::vector<std::string>{"camera", "transfer"}));
  EXPECT_EQ(c.criteria[1].criterion, "transfer.placed");
  EXPECT_EQ(c.criteria[1].sessions, 2);
  EXPECT_EQ(c.criteria[1].failing, 2);
  EXPECT_EQ(c.criteria[2].criterion, "transfer.drops");
  EXPECT_EQ(c.criteria[2].sessions, 1);
  EXPECT_EQ(c.criteria[2].failing, 0);  // below its limit, but it failed nothing
}

TEST(Cohort, TaskNamesComeFromTheTaskList) {
  const std::vector<Task> tasks = load_tasks(source("config/tasks.toml"));
  const TaskNames names(tasks);
  const Task& clip = find_task(tasks, "clip", "t");
  EXPECT_EQ(names.of(clip.scene, "clip_application"), "clip");  // the same file
  EXPECT_EQ(names.of("/other/checkout/config/clip_application.toml", "clip_application"), "clip");
  EXPECT_EQ(names.of("/x/cut_line.toml", "cut-line"), "cut-line");  // filed under its name
  EXPECT_EQ(names.of("/x/mine.toml", "mine"), "mine");
  EXPECT_EQ(TaskNames().of("/x/cut_line.toml", "cut_line"), "cut_line");  // no list: as stored
  EXPECT_EQ(task_name_for_scene(source("config/cut_line.toml")), "cut-line");
  EXPECT_EQ(task_name_for_scene("/nowhere/some_scene.toml"), "some_scene");
}

TEST(Cohort, TheCsvHasOneRowPerTraineeAndTaskQuoted) {
  std::vector<SessionRecord> s = three_trainees();
  s.push_back(session("Smith, \"Jo\"", "camera", 8, 81.25));
  const Cohort c = gather_cohort(s, shipped_names());
  const std::string csv = cohort_csv(c);
  EXPECT_EQ(std::count(csv.begin(), csv.end(), '\n'), 1 + 4 * 4);
  EXPECT_EQ(csv.substr(0, csv.find('\n')),
            "trainee,task,sessions,best,last,passed,last_passed,passes,pass_score");
  EXPECT_NE(csv.find("ann,camera,2,100.0,100.0,yes,yes,1,80.0\n"), std::string::npos) << csv;
  EXPECT_NE(csv.find("ann,transfer,0,,,no,no,0,\n"), std::string::npos) << csv;
  EXPECT_NE(csv.find("cy,transfer,1,40.0,40.0,no,no,0,80.0\n"), std::string::npos) << csv;
  EXPECT_NE(csv.find("\"Smith, \"\"Jo\"\"\",camera,1,81.2"), std::string::npos) << csv;
}

TEST(CohortPage, EscapesEveryTextAndFetchesNothing) {
  EXPECT_EQ(html_escape("<a href=\"x\">&'</a>"),
            "&lt;a href=&quot;x&quot;&gt;&amp;&#39;&lt;/a&gt;");
  const std::string evil = "<script>alert(\"x\")</script> & 'O'Neil'";
  std::vector<SessionRecord> s = three_trainees();
  s.push_back(session(evil, "<b>scene</b>", 9, 10.0, {"<i>metric</i> = 1, above the limit of 0"}));
  s.back().recording = "/gone/<rec> & \"x\".lapr";
  const Cohort c = gather_cohort(s, shipped_names());
  const std::string page = cohort_html(c, {out_dir("cohort_escape"), "/db/<p>.sqlite", "now"});
  EXPECT_EQ(page.find("<script"), std::string::npos);
  EXPECT_EQ(page.find("<b>"), std::string::npos);
  EXPECT_EQ(page.find("<i>"), std::string::npos);
  EXPECT_EQ(page.find("<rec>"), std::string::npos);
  EXPECT_NE(
      page.find("&lt;script&gt;alert(&quot;x&quot;)&lt;/script&gt; &amp; &#39;O&#39;Neil&#39;"),
      std::string::npos);
  EXPECT_NE(page.find("&lt;b&gt;scene&lt;/b&gt;"), std::string::npos);
  EXPECT_NE(page.find("/db/&lt;p&gt;.sqlite"), std::string::npos);
  // Nothing fetched: no script, stylesheet, image or frame from anywhere.
  for (const char* tag : {"<script", "<link", "<img", "<iframe", "src=", "@import", "url("})
    EXPECT_EQ(page.find(tag), std::string::npos) << tag;
}

TEST(CohortPage, HasTheTableCurvesPassRatesCriteriaAndSessions) {
  const fs::path dir = out_dir("cohort_parts");
  std::vector<SessionRecord> s = three_trainees();
  fs::create_directories(dir / "recordings");
  s[0].recording = (dir / "recordings" / "bo 1.lapr").string();
  std::ofstream(s[0].recording) << "x";
  s[0].report = "/elsewhere/r.json";  // not there
  const Cohort c = gather_cohort(s, shipped_names());
  const std::string page = cohort_html(c, {dir / "page", dir / "p.sqlite", "2026-12-03T10:00:00Z"});
  for (const char* id :
       {"id=\"table\"", "id=\"curves\"", "id=\"pass-rate\"", "id=\"criteria\"", "id=\"sessions\""})
    EXPECT_NE(page.find(id), std::string::npos) << id;
  std::size_t curves = 0;
  for (std::size_t at = 0; (at = page.find("<svg class=\"curve\"", at)) != std::string::npos; ++at)
    ++curves;
  EXPECT_EQ(curves, 3u);
  EXPECT_NE(page.find("<svg class=\"bars\""), std::string::npos);
  EXPECT_NE(page.find("stroke-dasharray"), std::string::npos);  // the pass score
  EXPECT_NE(page.find("<polyline"), std::string::npos);
  // The recording beside the page's folder: linked relatively, with its replay command.
  EXPECT_NE(page.find("href=\"../recordings/bo%201.lapr\""), std::string::npos);
  EXPECT_NE(page.find("serosa replay &#39;" + s[0].recording + "&#39;"), std::string::npos);
  // The report that is not there: shown missing, not linked.
  EXPECT_NE(page.find("missing</span> (was <code>/elsewhere/r.json</code>)"), std::string::npos);
  EXPECT_EQ(page.find("r.json\""), std::string::npos);
  EXPECT_NE(page.find("score 52 &lt; 80; transfer.placed = 0 &lt; 1"), std::string::npos);
  EXPECT_NE(page.find("transfer.placed"), std::string::npos);
  EXPECT_NE(page.find("1 of 2 trainees passed (1 of 3 sessions)"), std::string::npos);
}

TEST(CohortPage, LinksAreRelativeBesideThePageElseFileUrls) {
  EXPECT_EQ(file_href("/data/recordings/a b.lapr", "/data/page"), "../recordings/a%20b.lapr");
  EXPECT_EQ(file_href("/data/page/x/#1.json", "/data/page"), "x/%231.json");
  EXPECT_EQ(file_href("/home/u/rec.lapr", "/data/page"), "file:///home/u/rec.lapr");
  EXPECT_EQ(file_href("/rec.lapr", "/page"), "file:///rec.lapr");
  EXPECT_EQ(short_reason(kUnder), "score 52 < 80");
  EXPECT_EQ(short_reason(kPlaced), "transfer.placed = 0 < 1");
  EXPECT_EQ(criterion_of(kDrops), "transfer.drops");
}

// A database as the first Serosa with progress wrote it (schema version 1).
void write_version_1(const fs::path& file,
                     const std::vector<std::pair<std::string, double>>& rows) {
  sqlite3* db = nullptr;
  ASSERT_EQ(sqlite3_open(file.c_str(), &db), SQLITE_OK);
  std::string sql =
      "CREATE TABLE trainee (id INTEGER PRIMARY KEY, name TEXT NOT NULL UNIQUE);"
      "CREATE TABLE session (id INTEGER PRIMARY KEY, trainee_id INTEGER NOT NULL, task TEXT NOT "
      "NULL, scene TEXT NOT NULL, started_utc TEXT NOT NULL, simulated_s REAL NOT NULL, score "
      "REAL, passed INTEGER, domains TEXT NOT NULL, recording TEXT NOT NULL, report TEXT NOT "
      "NULL);"
      "INSERT INTO trainee(name) VALUES('ann'); PRAGMA user_version = 1;";
  for (const auto& [report, score] : rows)
    sql +=
        "INSERT INTO session(trainee_id, task, scene, started_utc, simulated_s, score, passed, "
        "domains, recording, report) VALUES(1, 'transfer', '/c/transfer.toml', "
        "'2026-01-01T00:00:00Z', 1.0, " +
        std::to_string(score) + ", 0, '{}', '', '" + report + "');";
  ASSERT_EQ(sqlite3_exec(db, sql.c_str(), nullptr, nullptr, nullptr), SQLITE_OK);
  sqlite3_close(db);
}

TEST(ProgressDb, AVersion1DatabaseIsUpgradedWithTheReasonsItsReportsStillHold) {
  const fs::path dir = out_dir("progress_upgrade");
  const fs::path kept = dir / "kept.json";
  std::ofstream(kept) << R"({"assessment": {"score": 46, "passed": false, "pass_score": 80,
      "failed": [")" << kUnder
                      << R"("], "below_threshold": [")" << kDrops << R"("]}})";
  write_version_1(dir / "p.sqlite", {{kept.string(), 46.0}, {(dir / "gone.json").string(), 30.0}});
  {
    const std::vector<SessionRecord> s = ProgressDb(dir / "p.sqlite").sessions("ann");
    ASSERT_EQ(s.size(), 2u);
    EXPECT_TRUE(s[0].reasons_known);
    EXPECT_EQ(s[0].failed, std::vector<std::string>{kUnder});
    EXPECT_EQ(s[0].below_threshold, std::vector<std::string>{kDrops});
    EXPECT_EQ(s[0].pass_score, 80.0);
    EXPECT_FALSE(s[1].reasons_known);  // its report had gone
    EXPECT_EQ(why_failed(s[1]).substr(0, 9), "not known");
  }
  sqlite3* db = nullptr;
  ASSERT_EQ(sqlite3_open((dir / "p.sqlite").c_str(), &db), SQLITE_OK);
  sqlite3_stmt* q = nullptr;
  sqlite3_prepare_v2(db, "PRAGMA user_version", -1, &q, nullptr);
  ASSERT_EQ(sqlite3_step(q), SQLITE_ROW);
  EXPECT_EQ(sqlite3_column_int(q, 0), 2);
  sqlite3_finalize(q);
  sqlite3_close(db);
  // Read again: nothing upgraded twice, the reasons stay.
  EXPECT_EQ(ProgressDb(dir / "p.sqlite").sessions("ann")[0].failed.size(), 1u);
}

TEST(ProgressDb, SessionsKeepTheirReasonsAndPassScore) {
  const fs::path dir = out_dir("progress_reasons");
  {
    ProgressDb db(dir / "p.sqlite");
    db.add(session("ann", "transfer", 1, 46.0, {kUnder, kPlaced}, {kPlaced, kDrops}));
  }
  const SessionRecord s =
      ProgressDb(dir / "p.sqlite", ProgressDb::Open::existing).sessions("ann")[0];
  EXPECT_EQ(s.failed, (std::vector<std::string>{kUnder, kPlaced}));
  EXPECT_EQ(s.below_threshold, (std::vector<std::string>{kPlaced, kDrops}));
  EXPECT_EQ(s.pass_score, 80.0);
  EXPECT_EQ(why_failed(s), "score 52 < 80; transfer.placed = 0 < 1");
}

CliResult cohort(const fs::path& db, const fs::path& dir) {
  return run_serosa("cohort --db '" + db.string() + "' --html '" + dir.string() + "'");
}

TEST(CohortCli, AMissingForeignOrNonSqliteDatabaseIsAClearError) {
  const fs::path dir = out_dir("cohort_bad_db");
  const fs::path missing = dir / "none.sqlite";
  for (const std::string& cmd : {std::string("cohort --html '") + (dir / "page").string() + "'",
                                 std::string("trainee ann"), std::string("trainee")}) {
    const CliResult r = run_serosa(cmd + " --db '" + missing.string() + "'");
    EXPECT_EQ(r.code, 1) << cmd << r.out;
    EXPECT_NE(r.out.find(missing.string() + ": no progress database here"), std::string::npos)
        << r.out;
    EXPECT_NE(r.out.find("--trainee"), std::string::npos) << r.out;  // how one is made
  }
  EXPECT_FALSE(fs::exists(missing));  // reading made none

  const fs::path foreign = dir / "foreign.sqlite";
  sqlite3* f = nullptr;
  ASSERT_EQ(sqlite3_open(foreign.c_str(), &f), SQLITE_OK);
  sqlite3_exec(f, "CREATE TABLE orders(id, item)", nullptr, nullptr, nullptr);
  sqlite3_close(f);
  const CliResult r = cohort(foreign, dir / "page");
  EXPECT_EQ(r.code, 1) << r.out;
  EXPECT_NE(r.out.find(foreign.string() + ": not a Serosa progress database: another program's "
                                          "SQLite database (user_version 0, tables: orders)"),
            std::string::npos)
      << r.out;

  const fs::path text = dir / "notes.txt";
  std::ofstream(text) << "these are not the sessions you are looking for\n"
                      << std::string(600, '.');
  const CliResult t = cohort(text, dir / "page");
  EXPECT_EQ(t.code, 1) << t.out;
  EXPECT_NE(t.out.find(text.string() + ": not a Serosa progress database: not a SQLite file"),
            std::string::npos)
      << t.out;

  const fs::path empty = dir / "empty.sqlite";
  std::ofstream(empty).flush();
  const CliResult e = cohort(empty, dir / "page");
  EXPECT_EQ(e.code, 1) << e.out;
  EXPECT_NE(e.out.find("an empty database"), std::string::npos) << e.out;
  EXPECT_FALSE(fs::exists(dir / "page" / "index.html"));
}

TEST(CohortCli, AMovedRecordingIsAWarningAndShownMissingOnThePageStillWritten) {
  const fs::path dir = out_dir("cohort_moved");
  const fs::path db = dir / "p.sqlite";
  {
    ProgressDb progress(db);
    for (int i = 1; i <= 2; ++i) {
      SessionRecord s = session("ann", "camera", i, 100.0);
      s.recording = (dir / "recordings" / ("s" + std::to_string(i) + ".lapr")).string();
      s.report = (dir / "recordings" / ("s" + std::to_string(i) + ".json")).string();
      fs::create_directories(dir / "recordings");
      std::ofstream(s.recording) << "lapr";
      std::ofstream(s.report) << "{}";
      progress.add(s);
    }
  }
  fs::rename(dir / "recordings" / "s2.lapr", dir / "moved.lapr");
  const fs::path csv = dir / "t.csv";
  const CliResult r = run_serosa("cohort --db '" + db.string() + "' --html '" +
                                 (dir / "page").string() + "' --csv '" + csv.string() + "'");
  ASSERT_EQ(r.code, 0) << r.out;
  const std::string gone = (dir / "recordings" / "s2.lapr").string();
  EXPECT_NE(r.out.find("warning: " + gone + ": not there"), std::string::npos) << r.out;
  const std::string page = file_text(dir / "page" / "index.html");
  EXPECT_NE(page.find("<a href=\"../recordings/s1.lapr\">"), std::string::npos);
  EXPECT_NE(page.find("missing</span> (was <code>" + gone + "</code>)"), std::string::npos);
  EXPECT_EQ(page.find("href=\"../recordings/s2.lapr\""), std::string::npos);
  EXPECT_EQ(page.find("serosa replay &#39;" + gone), std::string::npos);      // nothing to replay
  EXPECT_NE(page.find("href=\"../recordings/s2.json\""), std::string::npos);  // its report stayed
  EXPECT_NE(file_text(csv).find("ann,camera,2,100.0,100.0,yes,yes,2,80.0"), std::string::npos);
}

TEST(CohortCli, TraineeWithoutANameListsTheTraineesAndPointsToTheCohort) {
  const fs::path dir = out_dir("cohort_trainee_list");
  const fs::path db = dir / "p.sqlite";
  {
    ProgressDb progress(db);
    for (const SessionRecord& s : three_trainees()) progress.add(s);
  }
  const CliResult r = run_serosa("trainee --db '" + db.string() + "' --tasks '" +
                                 source("config/tasks.toml").string() + "'");
  ASSERT_EQ(r.code, 0) << r.out;
  EXPECT_NE(r.out.find("3 trainees in " + db.string()), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("ann                          3      2             2"), std::string::npos)
      << r.out;
  EXPECT_NE(r.out.find("serosa cohort"), std::string::npos) << r.out;
  const CliResult one = run_serosa("trainee bo --db '" + db.string() + "' --tasks '" +
                                   source("config/tasks.toml").string() + "'");
  ASSERT_EQ(one.code, 0) << one.out;
  EXPECT_NE(one.out.find("pass at"), std::string::npos) << one.out;
  EXPECT_NE(one.out.find("     failed: score 52 < 80; transfer.placed = 0 < 1\n"),
            std::string::npos)
      << one.out;
}

TEST(CohortCli, EveryOptionIsInTheReadmeSynopsis) {
  const std::string readme = file_text(source("README.md"));
  const auto at = readme.find("| `serosa cohort ");
  ASSERT_NE(at, std::string::npos);
  const std::string synopsis = readme.substr(at, readme.find("` |", at) - at);
  const CliResult help = run_serosa("cohort --help");
  ASSERT_EQ(help.code, 0) << help.out;
  for (const char* o : {"--db", "--html", "--csv", "--tasks"}) {
    EXPECT_NE(help.out.find(o), std::string::npos) << o;
    EXPECT_NE(synopsis.find(o), std::string::npos) << o;
  }
}

}  // namespace
}  // namespace serosa::app
