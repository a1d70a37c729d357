// `serosa batch` (app/batch_*.h, docs/batch.md) run as an engineer runs it: a manifest's runs,
// two at once, merged into summary.json, JUnit XML and a Markdown page; a run that fails or
// outlives the timeout is reported failed with its log and the others' results are kept; --resume
// runs only what has no result (as a requeued Slurm array task does); --index runs one run; seeds
// perturb the path smoothly and reproducibly; a bad manifest is an error naming its line before
// anything runs.
#include <gtest/gtest.h>

#include <chrono>
#include <fstream>
#include <random>
#include <sstream>
#include <string>

#include <nlohmann/json.hpp>

#include "app_test_util.h"
#include "batch/batch_manifest.h"
#include "batch/batch_runner.h"
#include "batch/path_perturb.h"
#include "engine/input_error.h"
#include "engine/shell_command.h"

namespace serosa::batch {
namespace {

using namespace serosa::app::testing;

nlohmann::json read_json(const fs::path& p) {
  nlohmann::json j;
  std::ifstream(p) >> j;
  return j;
}

// A small manifest in `dir`: two seeds of the transfer drill, one plain run, one whose path is
// not a tool path (its headless run fails), one that outlives the timeout (10 s: the fine scene's
// whole path takes about 40 s; the others well under a second, some seconds under ASan).
fs::path small_manifest(const fs::path& dir) {
  std::ofstream(dir / "broken.csv") << "t,tool,px\n0,left-grasper,0\n";
  const std::string scene = source("config/transfer.toml").string();
  std::ofstream(dir / "m.toml") << "title = \"small\"\ntimeout = 10\n"
                                << "[[run]]\nname = \"drill\"\nscene = \"" << scene
                                << "\"\nsteps = 100\nseeds = [1, 2]\n"
                                << "[[run]]\nname = \"plain\"\nscene = \"" << scene
                                << "\"\nsteps = 100\n"
                                << "set = { \"solver.tolerance\" = 1e-4 }\n"
                                << "[[run]]\nname = \"broken\"\nscene = \"" << scene
                                << "\"\nsteps = 100\n"
                                << "path = \"broken.csv\"\n"
                                << "[[run]]\nname = \"slow\"\nscene = \""
                                << source("config/appendectomy_fine.toml").string() << "\"\n";
  return dir / "m.toml";
}

TEST(Batch, RunsTwoAtOnceReportsFailuresWithTheirLogsAndResumes) {
  const fs::path dir = out_dir("batch_small");
  fs::remove_all(dir / "out");
  const fs::path m = small_manifest(dir);
  const std::string cmd =
      "batch " + shell_quote(m.string()) + " --out " + shell_quote((dir / "out").string());
  const CliResult first = run_serosa(cmd + " --jobs 2");
  EXPECT_EQ(first.code, 3) << first.out;  // some runs failed
  const nlohmann::json s = read_json(dir / "out/summary.json");
  ASSERT_EQ(s["runs"].size(), 5u) << s.dump(1);
  EXPECT_EQ(s["passed"], 3);
  std::map<std::string, nlohmann::json> by_id;
  for (const auto& r : s["runs"]) by_id[r["id"].get<std::string>()] = r;
  for (const char* id : {"drill.seed-1", "drill.seed-2", "plain"}) {
    EXPECT_EQ(by_id[id]["status"], "passed") << by_id[id].dump(1);
    EXPECT_TRUE(fs::is_regular_file(by_id[id]["report"].get<std::string>()));
    EXPECT_TRUE(fs::is_regular_file(by_id[id]["recording"].get<std::string>()));
    EXPECT_GT(by_id[id]["real_time_factor"].get<double>(), 0.0);
  }
  EXPECT_EQ(by_id["broken"]["status"], "failed");
  EXPECT_NE(by_id["broken"]["reason"].get<std::string>().find("broken.csv"), std::string::npos)
      << by_id["broken"].dump(1);
  EXPECT_TRUE(fs::is_regular_file(by_id["broken"]["log"].get<std::string>()));
  // The progress says why beneath a failed run's line: a CI log may be all there is to read.
  EXPECT_NE(first.out.find("broken                       failed"), std::string::npos) << first.out;
  EXPECT_NE(first.out.find(by_id["broken"]["reason"].get<std::string>()), std::string::npos)
      << first.out;
  EXPECT_EQ(by_id["slow"]["status"], "timeout") << by_id["slow"].dump(1);
  // The seeds perturbed the path: the two runs went different ways.
  EXPECT_NE(by_id["drill.seed-1"]["metrics"]["path_length_m"],
            by_id["drill.seed-2"]["metrics"]["path_length_m"]);
  // JUnit and the page.
  std::ostringstream junit;
  junit << std::ifstream(dir / "out/junit.xml").rdbuf();
  const std::string xml = junit.str();
  EXPECT_NE(xml.find("tests=\"5\" failures=\"2\""), std::string::npos) << xml;
  EXPECT_NE(xml.find("<failure message=\"timeout"), std::string::npos) << xml;
  EXPECT_TRUE(fs::is_regular_file(dir / "out/summary.md"));
  EXPECT_TRUE(fs::is_regular_file(dir / "out/time.png"));
  EXPECT_TRUE(fs::is_regular_file(dir / "out/spread.png"));

  // Resume: a run with a result is not run again; one whose result is gone (a task killed
  // before it finished) is.
  const fs::path kept = dir / "out/runs/plain/result.json";
  const auto when = fs::last_write_time(kept);
  fs::remove(dir / "out/runs/drill.seed-2/result.json");
  const CliResult again = run_serosa(cmd + " --resume");
  EXPECT_EQ(again.code, 3) << again.out;
  EXPECT_EQ(fs::last_write_time(kept), when);
  EXPECT_TRUE(fs::is_regular_file(dir / "out/runs/drill.seed-2/result.json"));
  EXPECT_EQ(read_json(dir / "out/summary.json")["passed"], 3);
  EXPECT_NE(again.out.find("kept: unchanged since its result"), std::string::npos) << again.out;

  // A run whose definition changed since its result runs again, and says so.
  std::stringstream text;
  text << std::ifstream(m).rdbuf();
  std::string changed = text.str();
  changed.replace(changed.find("1e-4"), 4, "2e-4");
  std::ofstream(m) << changed;
  const CliResult third = run_serosa(cmd + " --resume");
  EXPECT_EQ(third.code, 3) << third.out;
  EXPECT_NE(third.out.find("resume: plain changed since its result"), std::string::npos)
      << third.out;
  EXPECT_NE(fs::last_write_time(kept), when) << "the changed run was not run again";
  EXPECT_EQ(third.out.find("resume: drill.seed-1 changed"), std::string::npos) << third.out;
  std::ofstream(m) << text.str();

  // --index: one run alone, its result only, no merge.
  fs::remove_all(dir / "one");
  const CliResult one = run_serosa("batch " + shell_quote(m.string()) + " --out " +
                                   shell_quote((dir / "one").string()) + " --index 2");
  EXPECT_EQ(one.code, 0) << one.out;
  EXPECT_TRUE(fs::is_regular_file(dir / "one/runs/plain/result.json"));
  EXPECT_FALSE(fs::exists(dir / "one/runs/drill.seed-1"));
  EXPECT_FALSE(fs::exists(dir / "one/summary.json"));
}

// A run whose process dies by a signal is failed, saying which; its log is kept.
TEST(Batch, ACrashedRunIsFailedNamingTheSignal) {
  const fs::path dir = out_dir("batch_crash");
  fs::remove_all(dir / "out");
  std::ofstream(dir / "m.toml") << "[[run]]\nname = \"a\"\nscene = \""
                                << source("config/transfer.toml").string() << "\"\n";
  // A stand-in for serosa that crashes as soon as it starts.
  std::ofstream(dir / "crash.sh") << "#!/bin/sh\necho starting\nkill -SEGV $$\n";
  fs::permissions(dir / "crash.sh", fs::perms::owner_all);
  const BatchManifest m = load_manifest(dir / "m.toml", false);
  BatchOptions o;
  o.out = dir / "out";
  o.exe = dir / "crash.sh";
  const nlohmann::json r = run_one(m, m.runs[0], o);
  EXPECT_EQ(r["status"], "failed");
  EXPECT_EQ(r["signal"], 11);
  EXPECT_NE(r["reason"].get<std::string>().find("signal 11"), std::string::npos) << r.dump(1);
  std::ifstream log(r["log"].get<std::string>());
  std::string first;
  std::getline(log, first);
  EXPECT_EQ(first, "starting");
  EXPECT_TRUE(fs::is_regular_file(dir / "out/runs/a/result.json"));
}

// The manifest's mistakes name its line, before any run starts (no run folder is made).
TEST(Batch, ABadManifestIsAnErrorNamingTheLine) {
  const fs::path dir = out_dir("batch_bad");
  const std::string scene = source("config/transfer.toml").string();
  const std::string run = "[[run]]\nname = \"a\"\nscene = \"" + scene + "\"\n";
  struct Case {
    std::string text, says;
    int line;
  };
  const std::vector<Case> cases = {
      {"colour = 1\n" + run, "colour: unknown key", 1},
      {run + "speed = 2\n", "run[0].speed: unknown key", 4},
      {"[[run]]\nname = \"a\"\nscene = \"nowhere.toml\"\n", "no such scene", 3},
      {run + "set = { \"solver.tolerence\" = 1e-4 }\n", "solver.tolerence: unknown key", 3},
      {run + "set = { \"haptics.x\" = 1 }\n", "the scene has no [haptics]", 3},
      {run + "golden = \"g.json\"\nseeds = [1]\n", "seeds with a golden", 5},
      {run + "golden = \"absent.json\"\n", "no such golden", 4},
      {run + run, "a second run named 'a'", 5},
      {"title = \"t\"\n", "no [[run]] tables", 0},
      {"timeout = -1\n" + run, "timeout: not positive", 1},
      {run + "path = \"none.csv\"\n", "no such tool path", 4},
      {run + "golden = \"g.json\"\n[[run]]\nname = \"b\"\nscene = \"" + scene +
           "\"\ngolden = \"g.json\"\n",
       "is named by run 'a' too", 8},
  };
  std::ofstream(dir / "g.json") << "{}\n";
  for (const Case& c : cases) {
    SCOPED_TRACE(c.text);
    std::ofstream(dir / "m.toml") << c.text;
    try {
      (void)load_manifest(dir / "m.toml", false);
      ADD_FAILURE() << "no error";
    } catch (const InputError& e) {
      EXPECT_NE(std::string(e.what()).find(c.says), std::string::npos) << e.what();
      EXPECT_EQ(e.line(), c.line) << e.what();
    }
  }
  // On the command line: exit 1, nothing run.
  std::ofstream(dir / "m.toml") << run << "set = { \"solver.tolerence\" = 1e-4 }\n";
  fs::remove_all(dir / "out");
  const CliResult r = run_serosa("batch " + shell_quote((dir / "m.toml").string()) + " --out " +
                                 shell_quote((dir / "out").string()));
  EXPECT_EQ(r.code, 1) << r.out;
  EXPECT_NE(r.out.find("m.toml:3"), std::string::npos) << r.out;
  EXPECT_FALSE(fs::exists(dir / "out"));
}

// A golden mismatch's reason (summary, JUnit) names the first difference and the largest, each
// with both values: the cause is rarely the last line of the comparison (the state hash).
TEST(Batch, AMismatchNamesTheFirstAndTheLargestDifference) {
  const fs::path dir = out_dir("batch_mismatch");
  std::ofstream(dir / "m.toml") << "[[run]]\nname = \"g\"\nscene = \""
                                << source("config/transfer.toml").string() << "\"\n"
                                << "steps = 20\ngolden = \"g.json\"\n";
  const std::string cmd = "batch " + shell_quote((dir / "m.toml").string()) + " --out " +
                          shell_quote((dir / "out").string());
  fs::remove_all(dir / "out");
  ASSERT_EQ(run_serosa(cmd + " --update-golden").code, 0);
  nlohmann::json g = read_json(dir / "g.json");
  const double bimanual = g["metrics"]["bimanual_fraction"].get<double>();
  g["metrics"]["bimanual_fraction"] = bimanual + 1e-5;  // at most 10 tolerances off
  g["metrics"]["time_s"] = 0.2;                         // 500 tolerances (2e-4 s) off
  std::ofstream(dir / "g.json") << g.dump(2);
  fs::remove_all(dir / "out");
  const CliResult r = run_serosa(cmd);
  EXPECT_EQ(r.code, 3) << r.out;
  const std::string reason =
      read_json(dir / "out/summary.json")["runs"][0]["reason"].get<std::string>();
  EXPECT_EQ(reason.rfind("golden mismatch: /metrics/", 0), 0u) << reason;
  EXPECT_NE(reason.find("/metrics/bimanual_fraction: golden "), std::string::npos) << reason;
  EXPECT_NE(reason.find("largest: /metrics/time_s: golden 0.2, got 0.1"), std::string::npos)
      << reason;
  std::ostringstream junit;
  junit << std::ifstream(dir / "out/junit.xml").rdbuf();
  EXPECT_NE(junit.str().find("largest: /metrics/time_s"), std::string::npos) << junit.str();
}

// A scene with the rig in the loop steps at the wall clock's pace: the manifest marks it, and
// the batch runs it with nothing beside it (batch/run_gate.h); scripted scenes share the machine.
TEST(Batch, ARigInTheLoopMarksItsRunPaced) {
  const fs::path dir = out_dir("batch_paced");
  std::ofstream(dir / "m.toml") << "[[run]]\nname = \"rig\"\nscene = \""
                                << source("config/appendectomy_rig.toml").string() << "\"\n"
                                << "[[run]]\nname = \"script\"\nscene = \""
                                << source("config/appendectomy.toml").string() << "\"\n";
  const BatchManifest m = load_manifest(dir / "m.toml", false);
  ASSERT_EQ(m.runs.size(), 2u);
  EXPECT_TRUE(m.runs[0].paced);
  EXPECT_FALSE(m.runs[1].paced);
}

// A sweep expands into the cross product of its values (keys by name, values as listed), each
// run named by them and setting
// them over the run's own keys; with seeds, each combination runs each seed.
TEST(Batch, ASweepExpandsIntoEveryCombinationNamedByItsValues) {
  const fs::path dir = out_dir("batch_sweep");
  std::ofstream(dir / "m.toml") << "[[run]]\nname = \"s\"\nscene = \""
                                << source("config/transfer.toml").string() << "\"\n"
                                << "set = { \"solver.max_iterations\" = 50 }\n"
                                << "sweep = { \"solver.tolerance\" = [1e-3, 1e-4], "
                                << "\"solver.kind\" = [\"pcg\", \"cholmod\"] }\n"
                                << "seeds = [7]\n";
  const BatchManifest m = load_manifest(dir / "m.toml", false);
  ASSERT_EQ(m.runs.size(), 4u);
  const std::vector<std::string> ids = {
      "s.kind-pcg.tolerance-0.001.seed-7", "s.kind-pcg.tolerance-0.0001.seed-7",
      "s.kind-cholmod.tolerance-0.001.seed-7", "s.kind-cholmod.tolerance-0.0001.seed-7"};
  for (std::size_t k = 0; k < ids.size(); ++k) {
    EXPECT_EQ(m.runs[k].id, ids[k]);
    EXPECT_EQ(m.runs[k].group, "s");
    ASSERT_EQ(m.runs[k].overrides.size(), 3u);
    EXPECT_EQ(m.runs[k].overrides[0].key, "solver.max_iterations");
    EXPECT_EQ(m.runs[k].overrides[1].key, "solver.kind");  // keys in the order of their names
    EXPECT_EQ(m.runs[k].overrides[2].key, "solver.tolerance");
    EXPECT_EQ(m.runs[k].seed, 7u);
  }
  // A sweep of a key the scene does not have fails at its line, before anything runs.
  std::ofstream(dir / "bad.toml") << "[[run]]\nname = \"s\"\nscene = \""
                                  << source("config/transfer.toml").string() << "\"\n"
                                  << "sweep = { \"solver.tolerence\" = [1e-3] }\n";
  try {
    (void)load_manifest(dir / "bad.toml", false);
    ADD_FAILURE() << "no error";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("solver.tolerence"), std::string::npos) << e.what();
  }
}

// A seed moves every tip by a smooth offset no larger than the amplitude, the same each time;
// another seed moves it otherwise; orientations, jaws and buttons are kept. Over random paths.
TEST(Batch, SeedsPerturbPathsSmoothlyBoundedAndReproducibly) {
  std::mt19937 rng(5);
  std::uniform_real_distribution<double> u(-0.05, 0.05);
  for (int trial = 0; trial < 200; ++trial) {
    ToolPath p;
    p.tools = {"a", "b"};
    p.samples.resize(2);
    for (auto& rows : p.samples)
      for (int k = 0; k < 50; ++k) {
        ToolState s;
        s.time_s = 0.02 * k;
        s.tip_m = {u(rng), u(rng), u(rng)};
        s.jaw_rad = 0.5;
        s.buttons = static_cast<std::uint32_t>(k % 3);
        rows.push_back(s);
      }
    const double amp = 2e-4;
    const ToolPath a = perturb_path(p, 7, amp), b = perturb_path(p, 7, amp),
                   c = perturb_path(p, 8, amp);
    double moved = 0.0, differs = 0.0;
    for (std::size_t t = 0; t < 2; ++t)
      for (std::size_t k = 0; k < 50; ++k) {
        for (std::size_t d = 0; d < 3; ++d) {
          const double off = a.samples[t][k].tip_m[d] - p.samples[t][k].tip_m[d];
          ASSERT_LE(std::abs(off), amp * (1.0 + 1e-12));
          ASSERT_EQ(a.samples[t][k].tip_m[d], b.samples[t][k].tip_m[d]);
          differs =
              std::max(differs, std::abs(a.samples[t][k].tip_m[d] - c.samples[t][k].tip_m[d]));
          moved = std::max(moved, std::abs(off));
          if (k > 0) {  // smooth: at most 2 pi f A per second between rows (f <= 2 Hz)
            const double prev = a.samples[t][k - 1].tip_m[d] - p.samples[t][k - 1].tip_m[d];
            ASSERT_LE(std::abs(off - prev), 2.0 * 3.1416 * 2.0 * amp * 0.02 * 1.01);
          }
        }
        EXPECT_EQ(a.samples[t][k].jaw_rad, p.samples[t][k].jaw_rad);
        EXPECT_EQ(a.samples[t][k].buttons, p.samples[t][k].buttons);
        EXPECT_EQ(a.samples[t][k].quat_wxyz, p.samples[t][k].quat_wxyz);
      }
    EXPECT_GT(moved, 0.1 * amp);
    EXPECT_GT(differs, 0.0);
  }
  // Written and read back: the same path.
  const fs::path dir = out_dir("batch_perturb");
  ToolPath p;
  p.tools = {"g"};
  p.samples = {{ToolState{}}};
  p.samples[0][0].tip_m = {0.01, 0.02, 0.03};
  p.samples[0][0].quat_wxyz = {1.0, 0.0, 0.0, 0.0};
  write_tool_path(perturb_path(p, 3, 1e-4), dir / "p.csv");
  const ToolPath back = read_tool_path(dir / "p.csv");
  EXPECT_EQ(back.samples[0][0].tip_m, perturb_path(p, 3, 1e-4).samples[0][0].tip_m);
}

}  // namespace
}  // namespace serosa::batch
