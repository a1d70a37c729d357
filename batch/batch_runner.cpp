#include "batch/batch_runner.h"

#include <fcntl.h>
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <atomic>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <mutex>
#include <thread>

#include "batch/path_perturb.h"
#include "batch/run_fingerprint.h"
#include "batch/run_gate.h"
#include "engine/scene/scene.h"

namespace serosa::batch {
namespace {

namespace fs = std::filesystem;
using Json = nlohmann::json;

// The tool path a seeded run perturbs: the run's own, else the scene's first script.
fs::path base_path(const BatchRun& r) {
  if (r.path) return *r.path;
  const Scene scene = load_scene(r.scene, r.overrides);
  for (const Tool& t : scene.tools)
    if (t.device.kind == DeviceKind::kScript) return t.device.script;
  throw std::runtime_error("scene " + r.scene.string() + " has no scripted tool to perturb");
}

std::vector<std::string> headless_args(const BatchRun& r, const BatchOptions& o,
                                       const fs::path& dir) {
  std::vector<std::string> a = {o.exe.string(),
                                "headless",
                                r.scene.string(),
                                "--report",
                                (dir / "report.json").string(),
                                "--record",
                                (dir / "run.lapr").string()};
  if (r.steps) a.insert(a.end(), {"--steps", std::to_string(*r.steps)});
  if (r.seed) {
    const ToolPath p = perturb_path(read_tool_path(base_path(r)), *r.seed, r.perturb_m);
    write_tool_path(p, dir / "path.csv");
    a.insert(a.end(), {"--path", (dir / "path.csv").string()});
  } else if (r.path) {
    a.insert(a.end(), {"--path", r.path->string()});
  }
  for (const SceneOverride& s : r.overrides) a.insert(a.end(), {"--set", s.key + "=" + s.value});
  if (r.strict) a.emplace_back("--strict");
  if (r.golden) {
    a.insert(a.end(), {"--golden", r.golden->string()});
    if (o.update_golden) a.emplace_back("--update-golden");
  }
  return a;
}

struct Exit {
  int code = -1;   // exit status; -1 when killed by a signal
  int signal = 0;  // the signal that ended it
  bool timed_out = false;
};

// This process's environment for a run; with runs side by side, OpenMP's threads sleep instead of
// spinning while they wait: two scenes of two spinning solver threads each on two cores stepped
// 25 times slower than one alone. (Only waiting changes: the results are the same.)
std::vector<std::string> run_environment(bool side_by_side) {
  std::vector<std::string> env;
  for (char** e = environ; *e != nullptr; ++e) env.emplace_back(*e);
  if (side_by_side && std::getenv("OMP_WAIT_POLICY") == nullptr)
    env.emplace_back("OMP_WAIT_POLICY=passive");
  return env;
}

std::vector<char*> pointers(const std::vector<std::string>& strings) {
  std::vector<char*> p;
  for (const std::string& s : strings) p.push_back(const_cast<char*>(s.c_str()));
  p.push_back(nullptr);
  return p;
}

// Starts argv with stdout and stderr into `log`; waits at most timeout_s, then stops it (SIGTERM,
// and SIGKILL 5 s later).
Exit run_process(const std::vector<std::string>& argv, const std::vector<std::string>& env,
                 const fs::path& log, double timeout_s) {
  const std::vector<char*> args = pointers(argv);
  const std::vector<char*> envp = pointers(env);
  const pid_t pid = fork();
  if (pid == 0) {
    const int fd = open(log.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
    if (fd >= 0) {
      dup2(fd, 1);
      dup2(fd, 2);
      close(fd);
    }
    setpgid(0, 0);  // its own group: a timeout stops what it started too
    execve(args[0], args.data(), envp.data());
    _exit(127);
  }
  Exit e;
  if (pid < 0) return e;
  setpgid(pid, pid);  // (as the child does: whichever comes first)
  const auto start = std::chrono::steady_clock::now();
  int status = 0;
  int sent = 0;
  while (waitpid(pid, &status, WNOHANG) == 0) {
    const double t =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    if (t > timeout_s && sent == 0) {
      e.timed_out = true;
      kill(-pid, SIGTERM);
      sent = 1;
    } else if (t > timeout_s + 5.0 && sent == 1) {
      kill(-pid, SIGKILL);
      sent = 2;
    }
    std::this_thread::sleep_for(std::chrono::milliseconds(20));
  }
  if (WIFEXITED(status)) e.code = WEXITSTATUS(status);
  if (WIFSIGNALED(status)) e.signal = WTERMSIG(status);
  return e;
}

// What went wrong, from the log: its last error line, else the golden comparison's first
// mismatch and, when another, the largest ("golden mismatch, largest: ...").
std::string reason_in(const fs::path& log) {
  std::ifstream in(log);
  std::string line, error, first, largest;
  const auto starts = [&](const char* s) { return line.rfind(s, 0) == 0; };
  while (std::getline(in, line)) {
    if (starts("error:") || starts("internal error:")) error = line;
    if (starts("golden mismatch:") && first.empty()) first = line;
    if (starts("golden mismatch, largest:")) largest = line;
  }
  if (!error.empty()) return error;
  if (largest.empty() || largest.substr(largest.find(':')) == first.substr(first.find(':')))
    return first;
  return first + "; " + largest.substr(std::string("golden mismatch, ").size());
}

Json result_of(const BatchRun& r, const fs::path& dir, const Exit& e, double wall_s) {
  Json j{{"id", r.id},
         {"group", r.group},
         {"scene", r.scene.string()},
         {"wall_s", wall_s},
         {"exit_code", e.code},
         {"signal", e.signal},
         {"log", (dir / "log.txt").string()},
         {"report", (dir / "report.json").string()},
         {"recording", (dir / "run.lapr").string()}};
  j["seed"] = r.seed ? Json(*r.seed) : Json(nullptr);
  j["steps"] = r.steps ? Json(*r.steps) : Json(nullptr);  // null: the scene's own
  j["overrides"] = Json::array();
  for (const SceneOverride& s : r.overrides)
    j["overrides"].push_back({{"key", s.key}, {"value", s.value}});
  j["status"] = e.timed_out ? "timeout" : e.code == 0 ? "passed" : "failed";
  // Exit 4 (--strict: the run warned) comes after the golden matched.
  const bool matched = e.code == 0 || e.code == 4;
  j["golden"] = !r.golden ? "none" : matched ? "match" : e.code == 3 ? "mismatch" : "unknown";
  std::string reason = e.timed_out     ? "stopped after the manifest's timeout"
                       : e.signal != 0 ? "killed by signal " + std::to_string(e.signal)
                                       : reason_in(dir / "log.txt");
  if (j["status"] != "passed" && reason.empty()) reason = "exit code " + std::to_string(e.code);
  j["reason"] = j["status"] == "passed" ? "" : reason;
  std::ifstream in(dir / "report.json");
  Json report;
  if (in && (in >> report, true) && report.is_object()) {
    j["real_time_factor"] = report.value("real_time_factor", Json(nullptr));
    j["simulated_time_s"] = report.value("simulated_time_s", Json(nullptr));
    j["metrics"] = report.value("metrics", Json::object());
  }
  return j;
}

void write_result(const fs::path& dir, const Json& j) {
  const fs::path tmp = dir / "result.json.tmp";
  {
    std::ofstream out(tmp);
    out << j.dump(2) << '\n';
  }
  fs::rename(tmp, dir / "result.json");
}

}  // namespace

void print_progress(std::size_t done, std::size_t total, const Json& result) {
  char bar[21];
  const std::size_t filled = total > 0 ? 20 * done / total : 20;
  for (std::size_t k = 0; k < 20; ++k) bar[k] = k < filled ? '#' : '.';
  bar[20] = '\0';
  std::fprintf(stderr, "[%s] %zu/%zu  %-28s %-8s %6.1f s\n", bar, done, total,
               result.value("id", "").c_str(), result.value("status", "?").c_str(),
               result.value("wall_s", 0.0));
  if (result.value("kept", false))
    std::fprintf(stderr, "    kept: unchanged since its result (--resume)\n");
  // Why, where a CI log is all there is to read.
  const std::string why = result.value("reason", "");
  if (!why.empty()) std::fprintf(stderr, "    %s\n", why.c_str());
}

fs::path run_dir(const BatchOptions& o, const BatchRun& r) { return o.out / "runs" / r.id; }

std::optional<Json> finished_result(const BatchOptions& o, const BatchRun& r) {
  std::ifstream in(run_dir(o, r) / "result.json");
  if (!in) return std::nullopt;
  try {
    Json j;
    in >> j;
    if (j.is_object() && j.value("id", "") == r.id) return j;
  } catch (const Json::exception&) {
  }
  return std::nullopt;  // unreadable: run it again
}

Json run_one(const BatchManifest& m, const BatchRun& r, const BatchOptions& o) {
  const std::string fingerprint = run_fingerprint(r, o.binary);
  if (o.resume)
    if (auto done = finished_result(o, r)) {
      if (done->value("fingerprint", "") == fingerprint) {
        (*done)["kept"] = true;
        return *done;
      }
      std::fprintf(stderr,
                   "resume: %s changed since its result (its scene, path, keys, golden or the "
                   "binary): running it again\n",
                   r.id.c_str());
    }
  const fs::path dir = run_dir(o, r);
  fs::remove_all(dir);  // a run interrupted before its result starts over
  fs::create_directories(dir);
  const auto start = std::chrono::steady_clock::now();
  Exit e;
  try {
    e = run_process(headless_args(r, o, dir), run_environment(o.jobs > 1 && !r.paced),
                    dir / "log.txt", m.timeout_s);
  } catch (const std::exception& x) {
    std::ofstream(dir / "log.txt", std::ios::app) << "error: " << x.what() << '\n';
    e.code = 1;
  }
  const double wall =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  Json j = result_of(r, dir, e, wall);
  j["fingerprint"] = fingerprint;
  if (o.update_golden && r.golden && (e.code == 0 || e.code == 4)) j["golden"] = "written";
  write_result(dir, j);
  return j;
}

std::vector<Json> run_all(const BatchManifest& m, const BatchOptions& o) {
  std::vector<Json> results(m.runs.size());
  std::atomic<std::size_t> next{0};
  std::mutex print;
  RunGate gate;
  std::size_t done = 0;
  auto worker = [&] {
    for (std::size_t i = next++; i < m.runs.size(); i = next++) {
      gate.enter(m.runs[i].paced);
      results[i] = run_one(m, m.runs[i], o);
      gate.leave(m.runs[i].paced);
      const std::lock_guard<std::mutex> lock(print);
      ++done;
      if (o.progress) print_progress(done, m.runs.size(), results[i]);
    }
  };
  std::vector<std::thread> threads;
  const int n = std::max(1, std::min<int>(o.jobs, static_cast<int>(m.runs.size())));
  for (int k = 0; k < n; ++k) threads.emplace_back(worker);
  for (std::thread& t : threads) t.join();
  return results;
}

}  // namespace serosa::batch
