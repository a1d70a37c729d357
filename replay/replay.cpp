#include "replay/replay.h"

#include <spdlog/spdlog.h>
#include <unistd.h>

#include <chrono>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <span>

#include "app/assessment_report.h"
#include "app/compose.h"
#include "app/headless.h"
#include "app/output_paths.h"
#include "app/run_warnings.h"
#include "app/simulation.h"
#include "app/version.h"
#include "engine/input_error.h"
#include "engine/runner.h"
#include "engine/scene/scene.h"
#include "engine/sim_state.h"
#include "metrics/metrics_stage.h"
#include "recording/record_stage.h"
#include "recording/recording_reader.h"
#include "replay/old_snapshots.h"
#include "replay/recorded_scene.h"

namespace serosa::replay {

using namespace serosa::app;  // the driver, the composition and the window's parts
namespace {

using Json = nlohmann::json;

// The recording's last snapshot at or before simulated time t (none: nullptr).
const std::pair<const std::uint64_t, std::vector<std::uint8_t>>* snapshot_before(
    const recording::Recording& rec, double t_s, double dt_s) {
  const double k = std::isfinite(t_s) ? std::floor(std::max(t_s, 0.0) / dt_s + 1e-9) : 0.0;
  auto it = rec.snapshots.upper_bound(static_cast<std::uint64_t>(k));
  if (it == rec.snapshots.begin()) return nullptr;
  --it;
  return &*it;
}

// The first part of two snapshots that differs ("state" or a stage name), or empty when equal.
std::string first_difference(std::span<const std::uint8_t> replayed,
                             std::span<const std::uint8_t> recorded, const std::string& what) {
  if (std::equal(replayed.begin(), replayed.end(), recorded.begin(), recorded.end())) return {};
  const auto a = snapshot_sections(replayed, "replayed snapshot");
  const auto b = snapshot_sections(recorded, what);
  for (std::size_t i = 0; i < std::max(a.size(), b.size()); ++i) {
    if (i >= a.size()) return b[i].name;
    if (i >= b.size() || a[i].name != b[i].name) return a[i].name;
    const auto ra = replayed.subspan(a[i].offset, a[i].size);
    const auto rb = recorded.subspan(b[i].offset, b[i].size);
    if (std::equal(ra.begin(), ra.end(), rb.begin(), rb.end())) continue;
    const auto m = std::mismatch(ra.begin(), ra.end(), rb.begin(), rb.end());
    return a[i].name + " (byte " + std::to_string(m.first - ra.begin()) + " of " +
           std::to_string(ra.size()) + ", recorded " + std::to_string(rb.size()) + ")";
  }
  return "layout";
}

// --from past the recording's end: said, naming both, before the replay does what it always
// does (from the last snapshot, else from step 0).
std::vector<RunWarning> from_warnings(const std::string& file, double from_s, std::size_t steps,
                                      double dt_s, std::uint64_t start_step) {
  const double length_s = static_cast<double>(steps) * dt_s;
  if (!(from_s > length_s)) return {};
  char text[512];
  std::snprintf(text, sizeof text,
                "--from %.4g s is past the end of %s, which lasts %.4g s (%zu steps): replaying "
                "from step %llu (%.4g s)%s",
                from_s, file.c_str(), length_s, steps, static_cast<unsigned long long>(start_step),
                static_cast<double>(start_step) * dt_s,
                start_step > 0 ? ", its last snapshot" : ", the recording has no snapshot");
  return {{"from_past_end", text}};
}

}  // namespace

ReplayResult run_replay(const ReplayOptions& options) {
  // Its outputs' places first: a long replay must not end on a typo.
  if (options.report) check_output_file("--report", *options.report);
  if (options.frames) check_output_folder("--frames", *options.frames);
  const std::string file = options.recording.string();
  recording::Recording rec = recording::read_recording(options.recording);
  const std::optional<RunWarning> old_snapshots = drop_old_snapshots(rec, file);
  const Scene scene = recorded_scene(rec, file);

  ReplayResult result;
  result.damage = rec.stopped;
  result.corrupt = rec.corrupt;
  if (!rec.complete)
    spdlog::warn("{}: {}; replaying the {} steps before it", file, rec.stopped, rec.inputs.size());

  // The headless driver, fed the recorded inputs instead of the scene's devices and, with
  // verify, checking each recorded hash after the record slot.
  VerifyStage* verify = nullptr;
  SimulationHooks hooks;
  hooks.tool_input = [&rec] { return std::make_unique<ReplayInputStage>(rec.inputs); };
  if (options.verify)
    hooks.extend = [&rec, &verify](Runner& runner) {
      auto v = std::make_unique<VerifyStage>(rec.hashes);
      verify = v.get();
      runner.add(Slot::record, std::move(v));
    };
  hooks.quiet = true;
  const auto n = static_cast<std::uint64_t>(rec.inputs.size());
  HeadlessOptions driven;
  driven.steps = static_cast<std::int64_t>(n);
  driven.frames = options.frames;  // pictures spread over the replay, first and last included
  driven.frame_count = options.frame_count;
  driven.fitted_camera = options.fitted_camera;
  driven.progress = false;
  driven.scene_record = false;
  Simulation sim(scene, driven, std::move(hooks));
  std::vector<RunWarning> warnings;
  if (old_snapshots) {
    warnings.push_back(*old_snapshots);
    print_warnings(warnings);
  }
  if (options.from_s) {
    const auto* snap = snapshot_before(rec, *options.from_s, scene.settings.dt_s);
    if (snap == nullptr) {
      spdlog::info("{}: no snapshot at or before {} s; replaying from step 0", file,
                   *options.from_s);
    } else {
      sim.restore(snap->second, file + ": snapshot after step " + std::to_string(snap->first));
      result.start_step = snap->first;
    }
    std::vector<RunWarning> past_end = from_warnings(file, *options.from_s, rec.inputs.size(),
                                                     scene.settings.dt_s, result.start_step);
    print_warnings(past_end);
    warnings.insert(warnings.end(), past_end.begin(), past_end.end());
  }

  const SimState& state = sim.state();
  const Composition& comp = sim.composition();
  const auto t0 = std::chrono::steady_clock::now();
  for (std::uint64_t i = state.step; i < n; ++i) {
    sim.step();
    ++result.steps;
    if (verify && verify->divergence()) break;  // the first divergence ends the replay
    if (!verify) continue;
    if (const auto it = rec.snapshots.find(state.step); it != rec.snapshots.end()) {
      ++result.snapshots_checked;
      result.snapshot_part =
          first_difference(comp.runner->snapshot(state), it->second,
                           file + ": snapshot after step " + std::to_string(it->first));
      if (!result.snapshot_part.empty()) {
        result.snapshot_diverged_at = state.step;
        break;
      }
    }
  }
  const double wall = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();

  Json report = sim.picture_blocks();
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
  report["scene"] = rec.header.get("scene_path");
  if (!warnings.empty()) report["warnings"] = warnings_json(warnings);  // as the headless report's
  report["start_step"] = result.start_step;
  report["steps"] = result.steps;
  report["simulated_time_s"] = state.time_s;
  report["stepping_time_s"] = wall;
  report["state_hash"] = hash_hex(state_hash(state));
  report["mesh_final"] = {{"nodes", state.mesh.num_nodes()}, {"tets", state.mesh.num_tets()}};
  if (comp.cutting) report["cutting"] = cutting_json(comp);
  add_metrics_blocks(report, scene, comp.metrics, state.mesh, sim.assembled().group_names());
  if (verify) {
    result.hashes_checked = verify->checked();
    report["verify"] = {{"hashes_recorded", rec.hashes.size()},
                        {"hashes_checked", verify->checked()},
                        {"snapshots_recorded", rec.snapshots.size()},
                        {"snapshots_checked", result.snapshots_checked}};
    if (result.snapshot_diverged_at) {
      report["verify"]["snapshot_diverged_at_step"] = *result.snapshot_diverged_at;
      report["verify"]["snapshot_differs_in"] = result.snapshot_part;
    }
    if (const auto& d = verify->divergence()) {
      result.diverged_at = d->step;
      report["verify"]["diverged_at_step"] = d->step;
      report["verify"]["recorded_hash"] = hash_hex(d->recorded);
      report["verify"]["replayed_hash"] = hash_hex(d->replayed);
    }
    report["verify"]["ok"] = !result.diverged_at && !result.snapshot_diverged_at;
  }
  if (options.report) {
    std::ofstream out(*options.report);
    out << report.dump(2) << '\n';
  }
  result.report = std::move(report);
  return result;
}

}  // namespace serosa::replay
