#include "app/replay.h"

#include <spdlog/spdlog.h>
#include <unistd.h>

#include <chrono>
#include <cstdio>
#include <fstream>

#include "app/assemble_state.h"
#include "app/compose.h"
#include "app/frame_pictures.h"
#include "app/headless.h"
#include "app/version.h"
#include "engine/input_error.h"
#include "engine/record_stage.h"
#include "engine/recording_reader.h"
#include "engine/scene.h"
#include "engine/sim_state.h"
#include "metrics/metrics_stage.h"

namespace serosa::app {
namespace {

using Json = nlohmann::json;

}  // namespace

ReplayResult run_replay(const ReplayOptions& options) {
  const std::string file = options.recording.string();
  const recording::Recording rec = recording::read_recording(options.recording);
  const std::string scene_path = rec.header.get("scene_path");
  const std::string scene_text = rec.header.get("scene_text");
  if (scene_path.empty() || scene_text.empty())
    throw InputError(file, 0, "the header holds no scene", "scene_path and scene_text");
  const Scene scene = parse_scene_text(scene_text, scene_path);
  for (std::size_t s = 0; s < rec.inputs.size(); ++s)
    if (rec.inputs[s].size() != scene.tools.size())
      throw InputError(file, 0,
                       "step " + std::to_string(s) + " records " +
                           std::to_string(rec.inputs[s].size()) + " tools, the scene has " +
                           std::to_string(scene.tools.size()));

  ReplayResult result;
  result.damage = rec.stopped;
  result.corrupt = rec.corrupt;
  if (!rec.complete)
    spdlog::warn("{}: {}; replaying the {} steps before it", file, rec.stopped, rec.inputs.size());

  AssembledScene assembled = assemble_state(scene);
  ComposeOptions co;
  co.tool_input = std::make_unique<ReplayInputStage>(rec.inputs);
  Composition comp = compose(scene, assembled, std::move(co));
  VerifyStage* verify = nullptr;
  if (options.verify) {
    auto v = std::make_unique<VerifyStage>(rec.hashes);
    verify = v.get();
    comp.runner->add(Slot::record, std::move(v));
  }
  SimState& state = assembled.state;

  // Pictures spread over the replay, first and last included.
  std::unique_ptr<FramePictures> pictures;
  std::vector<std::uint64_t> picture_steps;
  const auto n = static_cast<std::uint64_t>(rec.inputs.size());
  Json report;
  if (options.frames) {
    pictures = std::make_unique<FramePictures>(*options.frames, scene, state.mesh,
                                               assembled.group_names());
    const int count = std::max(options.frame_count, 1);
    for (int k = 0; k < count; ++k)
      picture_steps.push_back(count == 1 ? n
                                         : n * static_cast<std::uint64_t>(k) /
                                               static_cast<std::uint64_t>(std::max(count - 1, 1)));
  }
  auto maybe_picture = [&](std::uint64_t step) {
    if (!pictures) return;
    if (std::find(picture_steps.begin(), picture_steps.end(), step) == picture_steps.end()) return;
    char stem[32];
    std::snprintf(stem, sizeof stem, "step_%06llu", static_cast<unsigned long long>(step));
    for (const auto& png : pictures->take(state, stem)) report["frames"].push_back(png.string());
  };

  const auto t0 = std::chrono::steady_clock::now();
  maybe_picture(0);
  for (std::uint64_t i = 0; i < n; ++i) {
    comp.runner->step(state);
    ++result.steps;
    if (verify && verify->divergence()) break;  // the first divergence ends the replay
    maybe_picture(i + 1);
  }
  const double wall = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();

  report["serosa"] = std::string(version_string());
  report["recording"] = {{"file", file},
                         {"recorded_by", rec.header.get("serosa")},
                         {"steps", n},
                         {"complete", rec.complete},
                         {"chunks", rec.chunks}};
  if (!rec.complete) {
    report["recording"]["stopped"] = rec.stopped;
    report["recording"]["stopped_at_byte"] = rec.stopped_at;
    report["recording"]["corrupt"] = rec.corrupt;
  }
  report["scene"] = scene_path;
  report["steps"] = result.steps;
  report["simulated_time_s"] = state.time_s;
  report["stepping_time_s"] = wall;
  report["state_hash"] = hash_hex(state_hash(state));
  report["mesh_final"] = {{"nodes", state.mesh.num_nodes()}, {"tets", state.mesh.num_tets()}};
  if (comp.cutting) report["cutting"] = cutting_json(comp);
  if (comp.metrics) report["metrics"] = comp.metrics->report();
  if (verify) {
    result.hashes_checked = verify->checked();
    report["verify"] = {{"hashes_recorded", rec.hashes.size()},
                        {"hashes_checked", verify->checked()}};
    if (const auto& d = verify->divergence()) {
      result.diverged_at = d->step;
      report["verify"]["diverged_at_step"] = d->step;
      report["verify"]["recorded_hash"] = hash_hex(d->recorded);
      report["verify"]["replayed_hash"] = hash_hex(d->replayed);
    }
    report["verify"]["ok"] = !result.diverged_at.has_value();
  }
  if (options.report) {
    if (options.report->has_parent_path())
      std::filesystem::create_directories(options.report->parent_path());
    std::ofstream out(*options.report);
    out << report.dump(2) << '\n';
  }
  result.report = std::move(report);
  return result;
}

}  // namespace serosa::app
