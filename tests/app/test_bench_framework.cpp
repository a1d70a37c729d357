// The `serosa bench` framework (bench/suite/bench_table.h, bench_registry.h): CSV writing and
// quoting, check_monotone catching violations and honouring its tolerances, the gnuplot script
// naming the right columns and refusing missing tables or columns, the runner reporting a part
// that throws, an empty table, a failed check, and summary.json.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>
#include <stdexcept>
#include <string>

#include "app_test_util.h"
#include "bench/suite/bench_registry.h"

namespace serosa::bench {
namespace {

namespace fs = std::filesystem;

std::string read_text(const fs::path& p) {
  std::ifstream is(p);
  std::stringstream ss;
  ss << is.rdbuf();
  return ss.str();
}

Table sweep(std::vector<double> knob, std::vector<double> value) {
  Table t{"sweep", {"knob", "error"}, {}, {}};
  for (std::size_t i = 0; i < knob.size(); ++i)
    t.add("k=" + std::to_string(i), {knob[i], value[i]});
  return t;
}

TEST(BenchTable, CsvQuotesSettingsAndWritesNineDigits) {
  const fs::path dir = app::testing::out_dir("bench_csv");
  Table t{"t", {"ms_per_step", "rel_error"}, {}, {}};
  t.add("cg tol=1e-4, warm", {1.5, 1.0 / 3.0});
  t.add("say \"hi\"", {2.0, 1e-12});
  t.write_csv(dir / "t.csv");
  EXPECT_EQ(read_text(dir / "t.csv"),
            "setting,ms_per_step,rel_error\n"
            "\"cg tol=1e-4, warm\",1.5,0.333333333\n"
            "\"say \"\"hi\"\"\",2,1e-12\n");
  EXPECT_THROW(t.add("short", {1.0}), std::invalid_argument);
  EXPECT_THROW((void)t.column("nope"), std::invalid_argument);
  EXPECT_THROW(t.write_csv(dir / "missing_folder" / "t.csv"), std::runtime_error);
}

TEST(BenchTable, CheckMonotoneFindsTheViolationInKnobOrder) {
  // Rows out of knob order: sorted by knob the error is 0.5, 0.1, 0.2 (up at knob 3).
  const Table t = sweep({3.0, 1.0, 2.0}, {0.2, 0.5, 0.1});
  MonotoneCheck c{"sweep", "knob", "error", Direction::decreasing, 0.0, 0.0, "falls"};
  const std::string v = check_monotone(t, c);
  EXPECT_NE(v.find("goes up from 0.1"), std::string::npos) << v;
  EXPECT_NE(v.find("'k=0'"), std::string::npos) << v;
  c.direction = Direction::increasing;
  EXPECT_NE(check_monotone(t, c).find("goes down from 0.5"), std::string::npos);
  // Sorted the other way it holds.
  EXPECT_EQ(check_monotone(sweep({1.0, 2.0, 3.0}, {0.5, 0.2, 0.1}),
                           {"sweep", "knob", "error", Direction::decreasing, 0.0, 0.0, ""}),
            "");
}

TEST(BenchTable, CheckMonotoneHonoursTolerances) {
  const Table t = sweep({1.0, 2.0, 3.0}, {1.0, 1.04, 1e-9});
  MonotoneCheck c{"sweep", "knob", "error", Direction::decreasing, 0.0, 0.0, ""};
  EXPECT_NE(check_monotone(t, c), "");  // up by 4%
  c.rel_tol = 0.05;
  EXPECT_EQ(check_monotone(t, c), "");  // within 5% of the previous value
  c.rel_tol = 0.03;
  EXPECT_NE(check_monotone(t, c), "");
  c.abs_tol = 0.05;
  EXPECT_EQ(check_monotone(t, c), "");  // 0.03 + 0.05 absolute
  // Non-finite values never pass; a missing column throws.
  const Table bad = sweep({1.0, 2.0}, {1.0, std::nan("")});
  EXPECT_NE(check_monotone(bad, {"sweep", "knob", "error", Direction::decreasing, 1.0, 1.0, ""})
                .find("not finite"),
            std::string::npos);
  EXPECT_THROW((void)check_monotone(t, {"sweep", "knob", "nope", Direction::decreasing, 0, 0, ""}),
               std::invalid_argument);
  // Fewer than two rows: nothing to violate.
  EXPECT_EQ(check_monotone(sweep({1.0}, {5.0}), c), "");
}

TEST(BenchGnuplot, ScriptNamesColumnsAndRefusesMissingOnes) {
  const Table t{"fem_cap", {"cap", "ms_per_step", "rel_error"}, {"a"}, {{1.0, 2.0, 3.0}}};
  Plot p{"fem",
         "it's a title",
         "ms",
         "error",
         true,
         true,
         {{"fem_cap", "ms_per_step", "rel_error", "CG", false, true}}};
  const std::string s = gnuplot_script(p, {t});
  // CSV column 1 is the setting: ms_per_step is column 3, rel_error column 4; log axes filter
  // non-positive values; the setting labels the points.
  EXPECT_NE(s.find("'fem_cap.csv' skip 1 using ($3 > 0 ? $3 : 1/0):($4 > 0 ? $4 : 1/0)"),
            std::string::npos)
      << s;
  EXPECT_NE(s.find(":1 with labels"), std::string::npos) << s;
  EXPECT_NE(s.find("set output 'fem.png'"), std::string::npos) << s;
  EXPECT_NE(s.find("'it''s a title'"), std::string::npos) << s;
  p.series[0].y = "missing_column";
  EXPECT_THROW((void)gnuplot_script(p, {t}), std::invalid_argument);
  p.series[0] = {"missing_table", "ms_per_step", "rel_error", "CG", false, false};
  EXPECT_THROW((void)gnuplot_script(p, {t}), std::invalid_argument);
  p.series.clear();
  EXPECT_THROW((void)gnuplot_script(p, {t}), std::invalid_argument);
}

PartResult good_part(const BenchOptions&) {
  PartResult r;
  r.tables.push_back(sweep({1.0, 2.0, 4.0}, {0.5, 0.2, 0.1}));
  r.plots.push_back({"sweep_plot",
                     "sweep",
                     "knob",
                     "error",
                     false,
                     true,
                     {{"sweep", "knob", "error", "error", false, true}}});
  r.checks.push_back({"sweep", "knob", "error", Direction::decreasing, 0.0, 0.0, "error falls"});
  r.notes.push_back("a note");
  return r;
}

PartResult bad_part(const BenchOptions&) {
  PartResult r;
  Table t = sweep({1.0, 2.0}, {0.1, 0.3});  // rises: the check fails
  t.name = "bad_sweep";
  r.tables.push_back(t);
  r.tables.push_back(Table{"empty", {"x"}, {}, {}});
  r.plots.push_back({"bad_plot",
                     "",
                     "",
                     "",
                     false,
                     false,
                     {{"bad_sweep", "knob", "no_such_column", "", false, false}}});
  r.checks.push_back({"bad_sweep", "knob", "error", Direction::decreasing, 0.0, 0.0, "falls"});
  return r;
}

PartResult throwing_part(const BenchOptions&) { throw std::runtime_error("solver exploded"); }

TEST(BenchRunner, ReportsEachFailureByPartAndWritesSummaryJson) {
  const fs::path dir = app::testing::out_dir("bench_runner");
  RunnerOptions o;
  o.bench.out = dir;
  o.plots = false;  // the CLI test draws; here only the scripts
  std::ostringstream log;
  const BenchReport good = run_parts({{"good", good_part}}, o, log);
  ASSERT_EQ(good.parts.size(), 1U);
  EXPECT_TRUE(good.ok()) << good.parts[0].problems.size();
  EXPECT_TRUE(fs::exists(dir / "sweep.csv"));
  EXPECT_TRUE(fs::exists(dir / "sweep_plot.gp"));

  const BenchReport r =
      run_parts({{"boom", throwing_part}, {"bad", bad_part}, {"good", good_part}}, o, log);
  ASSERT_EQ(r.parts.size(), 3U);
  EXPECT_FALSE(r.ok());
  EXPECT_EQ(r.parts[0].error, "solver exploded");
  EXPECT_FALSE(r.parts[0].ok());
  const PartReport& bad = r.parts[1];
  EXPECT_FALSE(bad.ok());
  ASSERT_EQ(bad.checks.size(), 1U);
  EXPECT_NE(bad.checks[0].violation.find("goes up"), std::string::npos);
  std::string problems;
  for (const auto& q : bad.problems) problems.append(q).append("\n");
  EXPECT_NE(problems.find("table 'empty' has no rows"), std::string::npos) << problems;
  EXPECT_NE(problems.find("no_such_column"), std::string::npos) << problems;
  EXPECT_TRUE(r.parts[2].ok());  // the others still ran

  write_summary_json(r, dir / "summary.json");
  const nlohmann::json j = nlohmann::json::parse(read_text(dir / "summary.json"));
  EXPECT_FALSE(j.at("ok").get<bool>());
  ASSERT_EQ(j.at("parts").size(), 3U);
  EXPECT_EQ(j.at("parts")[0].at("name"), "boom");
  EXPECT_EQ(j.at("parts")[0].at("error"), "solver exploded");
  EXPECT_FALSE(j.at("parts")[1].at("checks")[0].at("ok").get<bool>());
  EXPECT_TRUE(j.at("parts")[2].at("ok").get<bool>());
  EXPECT_EQ(j.at("parts")[2].at("notes")[0], "a note");

  std::ostringstream summary;
  print_summary(r, summary);
  EXPECT_NE(summary.str().find("ERROR: the part threw: solver exploded"), std::string::npos);
  EXPECT_NE(summary.str().find("check FAILED  falls"), std::string::npos);
}

TEST(BenchRegistry, ListsTheBuiltPartsOnceEach) {
  const auto& parts = registered_parts();
  ASSERT_FALSE(parts.empty());
  for (std::size_t i = 0; i < parts.size(); ++i)
    for (std::size_t j = i + 1; j < parts.size(); ++j) EXPECT_NE(parts[i].name, parts[j].name);
  EXPECT_FALSE(program_runs("/nonexistent/serosa-no-such-program"));
}

}  // namespace
}  // namespace serosa::bench
