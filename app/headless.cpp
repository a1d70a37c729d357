#include "app/headless.h"

#include <spdlog/spdlog.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <ctime>
#include <fstream>
#include <iterator>
#include <memory>
#include <numeric>
#include <sstream>
#include <thread>

#include "app/assemble_state.h"
#include "app/assessment_report.h"
#include "app/compose.h"
#include "app/frame_pictures.h"
#include "app/instrument_devices.h"
#include "app/output_paths.h"
#include "app/preset_report.h"
#include "app/provenance.h"
#include "app/run_series.h"
#include "app/run_warnings.h"
#include "app/version.h"
#include "contact/tool_contact_stage.h"
#include "cutting/cutting_stage.h"
#include "engine/input_error.h"
#include "engine/mesh_check.h"
#include "engine/mesh_io.h"
#include "engine/record_stage.h"
#include "engine/recording_writer.h"
#include "engine/scene.h"
#include "engine/script_tool_stage.h"
#include "engine/sim_state.h"
#include "fem/fem_stage.h"
#include "haptics/haptics_stage.h"
#include "metrics/metrics_stage.h"
#include "surface/surface_stage.h"

namespace serosa::app {
namespace {

using Json = nlohmann::json;

void progress_bar(std::int64_t done, std::int64_t total) {
  const int width = 40;
  const int filled = static_cast<int>(width * done / std::max<std::int64_t>(total, 1));
  std::fprintf(stderr, "\r[%.*s%*s] %lld/%lld steps", filled,
               "########################################", width - filled, "",
               static_cast<long long>(done), static_cast<long long>(total));
  if (done == total) std::fputc('\n', stderr);
}

Json mesh_json(const TetMesh& mesh) {
  const MeshCheckReport r = check_mesh(mesh);
  Json j;
  j["nodes"] = mesh.num_nodes();
  j["tets"] = mesh.num_tets();
  j["topology_version"] = mesh.topology_version;
  j["rest_volume_m3"] = r.volume_m3;
  j["valid"] = r.valid;
  j["min_quality"] = r.min_quality;
  return j;
}

std::string read_text(const std::filesystem::path& p) {
  std::ifstream in(p, std::ios::binary);
  std::ostringstream text;
  text << in.rdbuf();
  return text.str();
}

}  // namespace

Json close_recording(recording::RecordingWriter& writer, const Scene& scene, std::uint64_t steps) {
  writer.close(steps);
  const auto ws = writer.stats();
  return {{"file", writer.path().string()},
          {"steps", ws.steps},
          {"chunks", ws.chunks},
          {"bytes", ws.bytes},
          {"hash_every", scene.record.hash_every},
          {"snapshots", ws.snapshots}};
}

recording::Header recording_header(const Scene& scene, std::int64_t steps) {
  recording::Header h;
  h.set("serosa", std::string(version_string()));
  h.set("scene_path", std::filesystem::absolute(scene.file).lexically_normal().string());
  h.set("scene_text", read_text(scene.file));
  char buf[64];
  std::snprintf(buf, sizeof buf, "%.17g", scene.settings.dt_s);
  h.set("dt_s", buf);
  h.set("hash_every", std::to_string(scene.record.hash_every));
  std::string names;
  for (const Tool& t : scene.tools) {
    if (!names.empty()) names.push_back(',');
    names.append(t.name);
  }
  h.set("tools", names);
  h.set("steps_planned", std::to_string(steps));
  const std::time_t now = std::time(nullptr);
  std::tm utc{};
  gmtime_r(&now, &utc);
  std::strftime(buf, sizeof buf, "%Y-%m-%dT%H:%M:%SZ", &utc);
  h.set("created_utc", buf);
  return h;
}

// Each placed ligature (clip or loop: when, by which tool, what it clamps, where it is now) and
// the clips each applier closed on no tissue and the loops cinched round none.
Json clips_json(const Scene& scene, const SimState& state, const Composition& comp,
                const std::map<int, std::string>& group_names) {
  Json placed = Json::array();
  for (const Clip& c : state.handoff.clips) {
    Json groups = Json::array();
    for (int g : c.groups) {
      const auto it = group_names.find(g);
      groups.push_back(it != group_names.end() ? it->second : std::to_string(g));
    }
    const Vec3 mid = 0.5 * (c.end(0) + c.end(1));
    placed.push_back({{"tool", scene.tools[c.tool].name},
                      {"kind", c.kind == Clip::Kind::kLoop     ? "loop"
                               : c.kind == Clip::Kind::kStaple ? "staple"
                                                               : "clip"},
                      {"time_s", c.placed_s},
                      {"nodes", c.nodes},
                      {"groups", std::move(groups)},
                      {"centre_m", {mid.x(), mid.y(), mid.z()}}});
  }
  Json dropped = Json::object(), refused = Json::object();
  for (std::size_t i = 0; i < scene.tools.size(); ++i) {
    const ToolKind k = scene.tools[i].kind;
    if (k == ToolKind::kClipApplier || k == ToolKind::kEndoloop || k == ToolKind::kStapler)
      dropped[scene.tools[i].name] = comp.clips->dropped()[i];
    if (k == ToolKind::kStapler) refused[scene.tools[i].name] = comp.clips->refused()[i];
  }
  Json j = {{"placed", std::move(placed)}, {"dropped", std::move(dropped)}};
  if (!refused.empty()) j["refused"] = std::move(refused);  // fires on a ligature, per stapler
  return j;
}

Json cutting_json(const Composition& comp) {
  Json j = Json::object();
  if (comp.cutting) {
    const CuttingStageStats& c = comp.cutting->stats();
    j = {{"strokes", c.strokes},
         {"sweeps", c.sweeps},
         {"cuts", c.cuts},
         {"tets_removed", c.tets_removed},
         {"tets_added", c.tets_added},
         {"nodes_added", c.nodes_added},
         {"degenerate_tets", c.degenerate_tets},
         {"strokes_on_clip", c.strokes_on_clip},
         {"hook_strokes", c.hook_strokes},
         {"coagulated_nodes", c.coagulated_nodes}};
    if (comp.cutting->num_staplers() > 0) {
      j["stapler_fires"] = c.stapler_fires;
      j["stapler_fires_held"] = c.stapler_fires_held;
    }
    Json strokes = Json::array();
    for (const cutting::StrokeReport& r : c.stroke_reports)
      strokes.push_back({{"first_step", r.first_step},
                         {"last_step", r.last_step},
                         {"steps", r.steps},
                         {"polygons", r.polygons},
                         {"cuts", r.cuts},
                         {"tets_crossed", r.tets_crossed},
                         {"tets_created", r.tets_created},
                         {"pinned", r.pinned},
                         {"swept_area_m2", r.swept_area_m2},
                         {"crack_area_m2", r.crack_area_m2},
                         {"deviation_m", r.deviation_m},
                         {"bent", r.bent},
                         {"crack_deviation_m", r.crack_deviation_m},
                         {"min_quality", r.min_quality},
                         {"on_clip", r.on_clip}});
    j["per_stroke"] = std::move(strokes);
    if (c.validated > 0) {
      j["validated"] = c.validated;
      j["invalid"] = c.invalid;
      j["problems"] = c.problems;
    }
  }
  return j;
}

Json step_time_json(const std::vector<double>& ms, const std::vector<StepDetail>& details) {
  if (ms.empty()) return {{"p50", 0.0}, {"p99", 0.0}, {"max", 0.0}, {"slowest", Json::array()}};
  std::vector<std::size_t> order(ms.size());
  std::iota(order.begin(), order.end(), std::size_t{0});
  // Slowest first; equal times by step, so the report does not depend on the sort.
  std::sort(order.begin(), order.end(),
            [&](std::size_t a, std::size_t b) { return ms[a] != ms[b] ? ms[a] > ms[b] : a < b; });
  const auto at = [&](double q) {  // the q-quantile counted from the fastest step
    const auto k =
        std::min(ms.size() - 1, static_cast<std::size_t>(q * static_cast<double>(ms.size())));
    return ms[order[ms.size() - 1 - k]];
  };
  Json slowest = Json::array();
  for (std::size_t i = 0; i < std::min<std::size_t>(8, order.size()); ++i) {
    Json s = {{"step", order[i]}, {"ms", ms[order[i]]}};
    if (order[i] < details.size()) {
      const StepDetail& d = details[order[i]];
      s["fem_ms"] = d.fem_ms;
      s["cg_iterations"] = d.cg_iterations;
      s["factor_refresh"] = d.factor_refresh;
      s["factor_patch"] = d.factor_patch;
    }
    slowest.push_back(std::move(s));
  }
  return {{"p50", at(0.5)}, {"p99", at(0.99)}, {"max", ms[order[0]]}, {"slowest", slowest}};
}

namespace {

StepDetail step_detail(const Runner& runner, const fem::FemStage* fem) {
  StepDetail d;
  d.fem_ms = 1e3 * runner.last_stage_s("fem");
  if (fem != nullptr) {
    const fem::StepStatus& st = fem->last_status();
    d.cg_iterations = st.iterations;
    d.factor_refresh = st.factor_refresh;
    d.factor_patch = st.factor_patch;
  }
  return d;
}

// Every output the run will write, checked before anything runs; the final mesh's format.
std::optional<MeshOutputFormat> check_outputs(const HeadlessOptions& o) {
  if (o.report) check_output_file("--report", *o.report);
  if (o.record) check_output_file("--record", *o.record);
  if (o.series) check_output_file("--series", *o.series);
  if (o.frames) check_output_folder("--frames", *o.frames);
  if (o.vtu_series) check_output_folder("--vtu-series", *o.vtu_series);
  if (o.vtu_every < 1) throw InputError("--vtu-every", 0, "not positive", "steps >= 1");
  if (!o.export_final) return std::nullopt;
  check_output_file("--export-final", *o.export_final);
  return mesh_output_format("--export-final", *o.export_final);
}

std::int64_t steps_to_run(const HeadlessOptions& o, const Scene& scene) {
  if (o.seconds) {
    if (!(*o.seconds >= 0.0)) throw InputError("--seconds", 0, "negative", "seconds >= 0");
    return std::llround(*o.seconds / scene.settings.dt_s);
  }
  const std::int64_t steps = o.steps.value_or(scene.headless.steps);
  if (steps < 0) throw InputError("--steps", 0, "negative step count", ">= 0");
  return steps;
}

}  // namespace

std::string hash_hex(std::uint64_t hash) {
  char buf[17];
  std::snprintf(buf, sizeof buf, "%016llx", static_cast<unsigned long long>(hash));
  return buf;
}

Json run_headless(const HeadlessOptions& options) {
  const auto wall0 = std::chrono::steady_clock::now();
  const std::optional<MeshOutputFormat> final_format = check_outputs(options);
  Scene scene = load_scene(options.scene, options.overrides);
  if (options.tool_path) play_tool_path(scene, *options.tool_path);
  const std::int64_t steps = steps_to_run(options, scene);
  AssembledScene assembled = assemble_state(scene);
  ComposeOptions compose_options;
  compose_options.validate_cuts = options.validate_cuts;
  Composition comp = compose(scene, assembled, std::move(compose_options));
  SimState& state = assembled.state;
  // Record: the last stage, after everything the step changed.
  const std::unique_ptr<recording::RecordingWriter> writer =
      record_run(comp, scene, options.record, recording_header(scene, steps), "run");
  for (Effect e : comp.unavailable)
    spdlog::warn("effect '{}' is listed by {} but not implemented in this build: not simulated",
                 effect_name(e), scene.file.string());

  Json report;
  report["serosa"] = std::string(version_string());
  report["scene"] = scene.file.string();
  report["dt_s"] = scene.settings.dt_s;
  report["steps"] = steps;
  for (Effect e : comp.built) report["effects"]["simulated"].push_back(effect_name(e));
  for (Effect e : comp.folded) report["effects"]["folded"].push_back(effect_name(e));
  for (Effect e : comp.unavailable) report["effects"]["unavailable"].push_back(effect_name(e));
  report["mesh_initial"] = mesh_json(state.mesh);
  report["solver"] = solver_report(scene.solver);
  if (auto preset = preset_report(scene)) report["preset"] = std::move(*preset);
  report["fixed"] = fixed_json(assembled);
  report["provenance"] = provenance_json(scene, options.overrides, assembled);
  std::vector<RunWarning> warnings = selection_warnings(scene, assembled);
  print_warnings(warnings);  // before the run: an empty selection is known now

  std::unique_ptr<FramePictures> pictures;
  std::vector<std::int64_t> picture_steps;
  if (options.frames) {
    pictures = std::make_unique<FramePictures>(*options.frames, scene, state.mesh,
                                               assembled.group_names());
    pictures->set_endoscope(!options.fitted_camera);
    const int count = std::max(options.frame_count, 1);
    for (int k = 0; k < count; ++k)
      picture_steps.push_back(count == 1 ? steps : steps * k / std::max(count - 1, 1));
  }
  double render_s = 0.0;  // wall time spent drawing pictures
  std::int64_t rendered = 0;
  auto maybe_picture = [&](std::int64_t step) {
    if (!pictures) return;
    for (std::int64_t s : picture_steps)
      if (s == step) {
        const auto r0 = std::chrono::steady_clock::now();
        ++rendered;
        char stem[32];
        std::snprintf(stem, sizeof stem, "step_%06lld", static_cast<long long>(step));
        for (const auto& png : pictures->take(state, stem))
          report["frames"].push_back(png.string());
        report["frames_camera"] = pictures->camera_used();
        report["frames_flat"].push_back(pictures->flat_fraction());
        report["frames_blood"].push_back(pictures->blood_fraction());
        render_s += std::chrono::duration<double>(std::chrono::steady_clock::now() - r0).count();
        break;
      }
  };

  const bool bar = options.progress && isatty(STDERR_FILENO);
  const auto p0 = std::chrono::steady_clock::now();
  comp.runner->prepare(state);  // load time: FEM's structure and first factor
  const double prepare_ms =
      std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - p0).count();
  std::optional<StepSeries> series;
  if (options.series) series.emplace(*options.series, scene);
  std::optional<VtuSeries> vtu;
  if (options.vtu_series) vtu.emplace(*options.vtu_series, options.vtu_every);
  if (vtu) vtu->add(state);
  const auto sim0 = std::chrono::steady_clock::now();
  maybe_picture(0);
  std::int64_t taken = 0;
  std::vector<double> step_ms;  // wall time of each solver step (all stages), ms
  step_ms.reserve(static_cast<std::size_t>(steps));
  std::vector<StepDetail> details;  // where each step's time went
  details.reserve(static_cast<std::size_t>(steps));
  // A rig's hand moves in wall-clock time: step no faster than real time, or the run would end
  // before the hand got anywhere (slower is slow motion, as in the window).
  const bool paced = comp.haptics && comp.haptics->driven_by_rig();
  const auto pace0 = std::chrono::steady_clock::now();
  for (std::int64_t i = 0; i < steps; ++i) {
    if (options.stop && options.stop->load()) break;
    if (paced)
      std::this_thread::sleep_until(
          pace0 + std::chrono::duration_cast<std::chrono::steady_clock::duration>(
                      std::chrono::duration<double>(static_cast<double>(i) * scene.settings.dt_s)));
    const auto s0 = std::chrono::steady_clock::now();
    comp.runner->step(state);
    step_ms.push_back(
        std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - s0).count());
    details.push_back(step_detail(*comp.runner, comp.fem));
    if (series)
      series->add(state, step_ms.back(), details.back().fem_ms,
                  comp.fem ? comp.fem->last_status() : fem::StepStatus{});
    if (vtu) vtu->add(state);
    ++taken;
    maybe_picture(i + 1);
    if (bar && ((i + 1) % 10 == 0 || i + 1 == steps)) progress_bar(i + 1, steps);
  }
  if (bar && taken < steps) std::fputc('\n', stderr);
  report["steps_taken"] = taken;
  report["paced_to_real_time"] = paced;
  if (taken < steps) report["interrupted"] = true;
  if (comp.haptics) report["haptics"] = comp.haptics->telemetry_json();  // stops the loop
  if (writer)
    report["recording"] = close_recording(*writer, scene, static_cast<std::uint64_t>(taken));
  const double sim_s =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - sim0).count();

  for (const StageTiming& t : comp.runner->timings())
    report["time_per_stage_ms"][t.name] =
        t.calls ? 1e3 * t.total_s / static_cast<double>(t.calls) : 0.0;
  // Rendering is not a solver stage headless: ms per picture step, when pictures were drawn.
  if (rendered > 0)
    report["time_per_stage_ms"]["render"] = 1e3 * render_s / static_cast<double>(rendered);
  report["simulated_time_s"] = state.time_s;
  report["wall_time_s"] =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - wall0).count();
  report["stepping_time_s"] = sim_s;
  report["step_time_ms"] = step_time_json(step_ms, details);
  report["prepare_ms"] = prepare_ms;  // load time before the first step (Runner::prepare)
  // Simulated over wall time of the solver steps: >= 1 runs ahead of the clock.
  double stepped_s = 0.0;
  for (double ms : step_ms) stepped_s += 1e-3 * ms;
  report["real_time_factor"] = stepped_s > 0.0 ? state.time_s / stepped_s : 0.0;
  report["mesh_final"] = mesh_json(state.mesh);
  if (options.positions) {
    // For a golden: where every node ended, and which binary put it there (the state hash is
    // exact only for the same binary and thread count).
    Json nodes = Json::array();
    // To the nanometre: a golden compares them to 10 um, and the file stays small.
    const auto nm = [](double v) { return std::round(v * 1e9) / 1e9; };
    for (const Vec3& x : state.mesh.x) nodes.push_back({nm(x.x()), nm(x.y()), nm(x.z())});
    report["nodes_final_m"] = std::move(nodes);
    report["binary_id"] = binary_id();
  }
  for (const Blood& b : state.handoff.blood)
    report["bleeding"].push_back({{"since_s", b.since_s},
                                  {"shed_m3", b.shed_m3},
                                  {"pool_radius_m", b.pool_radius_m},
                                  {"flowing", b.pulse > 0.0}});
  report["state_hash"] = hash_hex(state_hash(state));
  if (comp.cutting) {
    report["cutting"] = cutting_json(comp);
    // The step each stroke was cut in, and the next (whose FEM takes the new tets), against dt;
    // kept out of "cutting", which a replay reproduces exactly.
    Json cut_steps = Json::array();
    for (const cutting::StrokeReport& r : comp.cutting->stats().stroke_reports) {
      const auto at = static_cast<std::size_t>(r.last_step);
      if (at >= step_ms.size()) continue;
      cut_steps.push_back({{"step", r.last_step},
                           {"ms", step_ms[at]},
                           {"next_ms", at + 1 < step_ms.size() ? step_ms[at + 1] : 0.0}});
    }
    report["cut_steps"] = std::move(cut_steps);
  }
  add_metrics_blocks(report, scene, comp.metrics, state.mesh, assembled.group_names());
  if (comp.contact) {
    const auto held = comp.contact->grasped_counts();
    for (std::size_t i = 0; i < scene.tools.size() && i < held.size(); ++i)
      if (scene.tools[i].kind == ToolKind::kGrasper)
        report["contact"]["held_nodes"][scene.tools[i].name] = held[i];
  }
  if (comp.clips) report["clips"] = clips_json(scene, state, comp, assembled.group_names());
  if (comp.surface) {
    const auto& ss = comp.surface->stats();
    report["surface"] = {
        {"faces", state.handoff.surface.num_faces()},
        {"rebuilds", ss.rebuilds},
        {"updates", ss.updates},
        {"failed_updates", ss.failed_updates},
        {"backend", comp.surface->backend() == surface::Backend::kCuda ? "cuda" : "cpu"}};
  }
  if (comp.fem) {
    const auto& st = comp.fem->stats();
    report["fem"] = {{"steps", st.steps},
                     {"not_converged", st.not_converged},
                     {"factor_refreshes", st.factor_refreshes},
                     {"factor_patches", st.factor_patches},
                     {"rejected", st.rejected},
                     {"energy_gains", st.energy_gains},
                     {"energy_gains_after_capped_solve", st.energy_gains_after_capped_solve},
                     {"energy_removed_j", st.energy_removed_j},
                     {"peak_energy_j", st.peak_energy_j},
                     {"last_iterations", comp.fem->last_status().iterations},
                     {"last_residual", comp.fem->last_status().residual},
                     {"debris_tets", comp.fem->integrator().elements().debris_tets},
                     {"debris_volume_m3", comp.fem->integrator().elements().debris_volume_m3}};
  }
  if (comp.fem) {
    const std::vector<RunWarning> solver = solver_warnings(scene.solver, comp.fem->stats());
    print_warnings(solver);
    warnings.insert(warnings.end(), solver.begin(), solver.end());
  }
  report["warnings"] = warnings_json(warnings);
  if (options.export_final) {
    write_mesh_output(*options.export_final, *final_format, state.mesh, assembled.group_names());
    report["export_final"] = options.export_final->string();
  }
  if (series) {
    series->close();
    report["series"] = options.series->string();
  }
  if (vtu)
    report["vtu_series"] = {{"folder", options.vtu_series->string()}, {"files", vtu->close()}};
  if (options.report) {
    std::ofstream out(*options.report);
    out << report.dump(2) << '\n';
    if (!out) throw std::runtime_error("cannot write report " + options.report->string());
  }
  return report;
}

}  // namespace serosa::app
