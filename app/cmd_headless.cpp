// serosa headless SCENE|--task NAME [--steps N|--seconds S] [--path TOOLPATH.csv]
//                       [--record OUT.lapr] [--export-final OUT.msh|.vtu|.obj] [--report OUT.json]
//                       [--series OUT.csv] [--vtu-series DIR [--vtu-every N]] [--frames DIR]
//                       [--golden GOLDEN.json [--update-golden]] [--validate-cuts]
//                       [--trainee NAME [--db FILE]] [--set KEY=VALUE ...] [--strict] [--json]
// Prints a short summary (app/run_summary.h), or with --json the whole report, on stdout.
// Exit codes: 0 done; 1 bad input; 3 the report differs from the golden (or it is missing);
// 4 with --strict, the run warned (app/run_warnings.h: the solver left steps above its tolerance,
// gained energy or rejected a step, a fixed selection picked nothing, a --path outlasted the
// scene's steps). A golden mismatch wins.
// Ctrl-C or SIGTERM stops after the current step with the recording closed and the report written.
#include <atomic>
#include <csignal>
#include <cstdio>
#include <memory>

#include "app/camera_option.h"
#include "app/command.h"
#include "app/emulated_rig_process.h"
#include "app/headless.h"
#include "app/run_summary.h"
#include "batch/golden.h"
#include "engine/input_error.h"
#include "engine/scene/scene.h"
#include "trainee/task_option.h"
#include "trainee/trainee_session.h"

namespace serosa::app {

using namespace serosa::trainee;
namespace {

// Ctrl-C (SIGINT) or SIGTERM ends the run after the current step, cleanly: the recording is
// closed and the report written. A signal handler can only reach a flag with static storage.
std::atomic<bool> g_stop_requested{false};  // NOLINT: the one signal flag

extern "C" void request_stop(int /*signal*/) { g_stop_requested.store(true); }

// 4 when --strict and the report lists warnings, saying so as an error (a batch's reason);
// else 0.
int strict_exit(const nlohmann::json& report, bool strict) {
  const auto it = report.find("warnings");
  if (!strict || it == report.end() || it->empty()) return 0;
  std::fprintf(stderr, "error: --strict: the run warned %zu time(s); the first: %s\n", it->size(),
               (*it)[0].value("text", "").c_str());
  return 4;
}

}  // namespace

void add_headless_command(CLI::App& app, Action& action) {
  auto opts = std::make_shared<HeadlessOptions>();
  auto record = std::make_shared<std::string>();
  auto steps = std::make_shared<std::int64_t>(-1);
  auto path = std::make_shared<std::string>();
  auto final_msh = std::make_shared<std::string>();
  auto report = std::make_shared<std::string>();
  auto frames = std::make_shared<std::string>();
  auto golden = std::make_shared<std::string>();
  auto update_golden = std::make_shared<bool>(false);
  auto strict = std::make_shared<bool>(false);
  auto json_out = std::make_shared<bool>(false);
  auto trainee = std::make_shared<TraineeOptions>();
  auto sets = std::make_shared<std::vector<std::string>>();
  CLI::App* cmd = app.add_subcommand("headless", "Run a scene without window or device");
  auto scene = std::make_shared<std::string>();
  auto task = std::make_shared<TaskOption>();
  cmd->add_option("scene", *scene, "Scene TOML file (or --task NAME)");
  add_task_options(*cmd, *task);
  CLI::Option* steps_opt =
      cmd->add_option("--steps", *steps, "Solver steps (default: the scene's headless.steps)");
  cmd->add_option("--seconds", opts->seconds,
                  "Simulated seconds instead of --steps (a dt sweep keeps the time, not the steps)")
      ->excludes(steps_opt);
  cmd->add_option("--path", *path, "Tool path CSV replacing every scripted tool's path");
  cmd->add_option("--record", *record, "Record the run to a .lapr file");
  cmd->add_option("--export-final", *final_msh,
                  "Write the final state: .msh (Gmsh 2.2), .vtu (ParaView) or .obj (its surface)");
  cmd->add_option("--series", opts->series,
                  "Write a per-step CSV: time, step time, iterations, residual, energy, tool "
                  "forces");
  cmd->add_option("--vtu-series", opts->vtu_series,
                  "Write the mesh as VTU every --vtu-every steps into this folder, with a .pvd");
  cmd->add_option("--vtu-every", opts->vtu_every, "Steps between --vtu-series files (default 10)")
      ->check(CLI::Range(std::int64_t{1}, std::int64_t{1000000000}));
  cmd->add_option("--report", *report, "Write the JSON report here");
  cmd->add_flag("--json", *json_out, "Print the JSON report on stdout instead of a summary");
  cmd->add_option("--frames", *frames, "Write PNG pictures of the run into this folder");
  cmd->add_option("--golden", *golden,
                  "Compare the report with this golden report (exit 3 on a difference beyond "
                  "the tolerances, or when it is missing)");
  cmd->add_flag("--update-golden", *update_golden, "Write the report as the --golden file");
  cmd->add_flag("--validate-cuts", opts->validate_cuts,
                "Check every cut's invariants (slow; the report lists any problem)");
  cmd->add_option("--frame-count", opts->frame_count, "Pictures over the run (with --frames)")
      ->check(CLI::Range(1, 100000));
  add_camera_option(*cmd, opts->fitted_camera);
  add_trainee_options(*cmd, *trainee);
  cmd->add_flag("--strict", *strict,
                "Exit 4 when the run warned: steps the solver left above its tolerance, energy "
                "gained, steps rejected, a fixed selection that picked no node, a --path the "
                "scene's steps cut off");
  cmd->add_option("--set", *sets,
                  "Override a scene key, KEY=VALUE with a TOML value (solver.tolerance=1e-4); "
                  "repeatable");
  cmd->callback([&action, opts, record, steps, path, final_msh, report, frames, golden,
                 update_golden, trainee, scene, task, sets, strict, json_out] {
    action = [opts, record, steps, path, final_msh, report, frames, golden, update_golden, trainee,
              scene, task, sets, strict, json_out] {
      opts->scene = scene_to_run(*scene, *task);
      for (const std::string& s : *sets) opts->overrides.push_back(parse_override(s, "--set"));
      opts->positions = !golden->empty();
      if (*update_golden && golden->empty())
        throw InputError("--update-golden", 0, "needs --golden FILE", "--golden FILE");
      run_under_umockdev_if_rig_emulated(load_scene(opts->scene, opts->overrides));
      if (!record->empty()) opts->record = *record;
      if (!report->empty()) opts->report = *report;
      const std::optional<TraineeSession> kept =
          begin_trainee_session(*trainee, opts->scene, opts->record, opts->report);
      opts->stop = &g_stop_requested;
      std::signal(SIGINT, request_stop);
      std::signal(SIGTERM, request_stop);
      if (*steps >= 0) opts->steps = *steps;
      if (!path->empty()) opts->tool_path = *path;
      if (!final_msh->empty()) opts->export_final = *final_msh;
      if (!frames->empty()) opts->frames = *frames;
      const auto json = run_headless(*opts);
      if (*json_out)
        std::printf("%s\n", json.dump(2).c_str());
      else
        std::fputs(run_summary(json, {opts->report, opts->frames}).c_str(), stdout);
      std::fflush(stdout);  // whole, before stderr's lines: a log holding both reads in order
      if (kept)             // after the recording and the report are written
        file_session(*kept, opts->scene, json, opts->record, opts->report);
      if (golden->empty()) return strict_exit(json, *strict);
      const batch::GoldenComparison g = batch::check_golden(json, *golden, *update_golden);
      for (const std::string& n : g.notes) std::fprintf(stderr, "note: %s\n", n.c_str());
      for (const std::string& f : g.failures)
        std::fprintf(stderr, "golden mismatch: %s\n", f.c_str());
      if (g.failures.size() > 1)  // the cause is rarely the last line (the state hash)
        std::fprintf(stderr, "golden mismatch, largest: %s\n", g.failures[g.largest].c_str());
      if (!g.ok()) return 3;
      std::fprintf(stderr, "%s %s\n",
                   *update_golden ? "golden written:" : "golden matches:", golden->c_str());
      return strict_exit(json, *strict);
    };
  });
}

}  // namespace serosa::app
