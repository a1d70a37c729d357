// What `serosa headless` prints: a short summary a person reads (procedure, score, real time,
// warnings, where the files went), or with --json the whole report and nothing else, so a script
// parses stdout; the report file holds the same report either way.
#include <gtest/gtest.h>

#include <algorithm>
#include <string>

#include <nlohmann/json.hpp>

#include "app/run_summary.h"
#include "app_test_util.h"
#include "engine/shell_command.h"

namespace serosa::app {
namespace {

using namespace serosa::app::testing;
using Json = nlohmann::json;

// `serosa ARGS > stdout_file`, stderr captured apart (run_command adds 2>&1 to the whole group).
CliResult run_to_file(const std::string& args, const fs::path& stdout_file) {
  const Command c = run_command("{ " + shell_quote(serosa_exe().string()) + " " + args + " > " +
                                shell_quote(stdout_file.string()) + "; }");
  return {c.code, c.output};
}

std::size_t lines(const std::string& s) {
  return static_cast<std::size_t>(std::count(s.begin(), s.end(), '\n'));
}

TEST(RunSummary, SaysWhatWasNotDoneTheScoreAndTheFirstWarning) {
  const Json report = {
      {"scene", "config/x.toml"},
      {"mesh_initial", {{"tets", 4793}, {"nodes", 1432}}},
      {"steps", 1880},
      {"steps_taken", 1000},
      {"interrupted", true},
      {"simulated_time_s", 5.0},
      {"dt_s", 0.005},
      {"real_time_factor", 1.5},
      {"step_time_ms", {{"p99", 7.25}, {"max", 12.5}}},
      {"procedure",
       {{"completed", false},
        {"steps",
         {{{"name", "expose"}, {"done", true}}, {{"name", "transect"}, {"done", false}}}}}},
      {"assessment",
       {{"score", 62.5}, {"pass_score", 80.0}, {"passed", false}, {"failed", {"too slow"}}}},
      {"warnings", {{{"kind", "not_converged"}, {"text", "3 steps above tolerance"}}}},
      {"export_final", "out/final.msh"}};
  const std::string s = run_summary(report, {"out/report.json", "out/frames"});
  EXPECT_NE(s.find("1000 of 1880 (5.00 s simulated), interrupted"), std::string::npos) << s;
  EXPECT_NE(s.find("NOT completed, 1 of 2 steps; not done: transect"), std::string::npos) << s;
  EXPECT_NE(s.find("62.5 / 100 (pass 80): not passed; too slow"), std::string::npos) << s;
  EXPECT_NE(s.find("1.50x (step p99 7.2 ms, max 12.5 ms, dt 5.0 ms)"), std::string::npos) << s;
  EXPECT_NE(s.find("1; the first: 3 steps above tolerance"), std::string::npos) << s;
  EXPECT_NE(s.find("out/report.json"), std::string::npos) << s;
  EXPECT_NE(s.find("out/final.msh"), std::string::npos) << s;
  EXPECT_LE(lines(s), 12u) << s;
}

TEST(RunSummary, AReportWithoutAFileSaysHowToGetOne) {
  const std::string s = run_summary(Json::object(), {});
  EXPECT_NE(s.find("not written (--report FILE, or --json)"), std::string::npos) << s;
  EXPECT_NE(s.find("warnings   none"), std::string::npos) << s;
}

TEST(RunSummary, HeadlessPrintsTheSummaryAndWithJsonOnlyTheReport) {
  const fs::path dir = fs::temp_directory_path() / "serosa_run_summary";
  fs::remove_all(dir);
  fs::create_directories(dir);
  const std::string scene = source("config/transection.toml").string();
  const auto a = run_to_file(
      "headless " + scene + " --steps 20 --report " + (dir / "r.json").string(), dir / "out.txt");
  ASSERT_EQ(a.code, 0) << a.out;
  const std::string summary = file_text(dir / "out.txt");
  EXPECT_EQ(summary.find('{'), std::string::npos) << summary;
  EXPECT_NE(summary.find("20 of 20"), std::string::npos) << summary;
  EXPECT_NE(summary.find("real time"), std::string::npos) << summary;
  EXPECT_NE(summary.find((dir / "r.json").string()), std::string::npos) << summary;
  EXPECT_LE(lines(summary), 12u);
  const Json file = Json::parse(file_text(dir / "r.json"));

  const auto b = run_to_file("headless " + scene + " --steps 20 --json", dir / "out.json");
  ASSERT_EQ(b.code, 0) << b.out;
  const Json printed = Json::parse(file_text(dir / "out.json"));  // the whole of stdout
  EXPECT_EQ(printed.at("state_hash"), file.at("state_hash"));
  EXPECT_EQ(printed.at("steps_taken"), 20);
  fs::remove_all(dir);
}

}  // namespace
}  // namespace serosa::app
