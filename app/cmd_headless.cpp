// serosa headless SCENE [--steps N] [--path TOOLPATH.csv] [--record OUT.lapr]
//                       [--export-final OUT.msh] [--report OUT.json] [--frames DIR]
#include <cstdio>
#include <memory>

#include "app/command.h"
#include "app/headless.h"
#include "engine/input_error.h"

namespace serosa::app {

void add_headless_command(CLI::App& app, Action& action) {
  auto opts = std::make_shared<HeadlessOptions>();
  auto record = std::make_shared<std::string>();
  auto steps = std::make_shared<std::int64_t>(-1);
  auto path = std::make_shared<std::string>();
  auto final_msh = std::make_shared<std::string>();
  auto report = std::make_shared<std::string>();
  auto frames = std::make_shared<std::string>();
  CLI::App* cmd = app.add_subcommand("headless", "Run a scene without window or device");
  cmd->add_option("scene", opts->scene, "Scene TOML file")->required();
  cmd->add_option("--steps", *steps, "Solver steps (default: the scene's headless.steps)");
  cmd->add_option("--path", *path, "Tool path CSV replacing every scripted tool's path");
  cmd->add_option("--record", *record, "Record the run to a .lapr file");
  cmd->add_option("--export-final", *final_msh, "Write the final state as Gmsh 2.2");
  cmd->add_option("--report", *report, "Write the JSON report here (also printed)");
  cmd->add_option("--frames", *frames, "Write PNG pictures of the run into this folder");
  cmd->add_option("--frame-count", opts->frame_count, "Pictures over the run (with --frames)")
      ->check(CLI::Range(1, 100000));
  cmd->callback([&action, opts, record, steps, path, final_msh, report, frames] {
    action = [opts, record, steps, path, final_msh, report, frames] {
      if (!record->empty())
        throw InputError(*record, 0, "recording (.lapr) is not implemented in this build yet",
                         "a run without --record");
      if (*steps >= 0) opts->steps = *steps;
      if (!path->empty()) opts->tool_path = *path;
      if (!final_msh->empty()) opts->export_final = *final_msh;
      if (!report->empty()) opts->report = *report;
      if (!frames->empty()) opts->frames = *frames;
      const auto json = run_headless(*opts);
      std::printf("%s\n", json.dump(2).c_str());
      return 0;
    };
  });
}

}  // namespace serosa::app
