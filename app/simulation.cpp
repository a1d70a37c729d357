#include "app/simulation.h"

#include <spdlog/spdlog.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <stdexcept>
#include <thread>

#include "app/assessment_report.h"
#include "app/frame_pictures.h"
#include "app/instrument_devices.h"
#include "app/preset_report.h"
#include "app/provenance.h"
#include "app/run_report.h"
#include "app/version.h"
#include "contact/tool_contact_stage.h"
#include "cutting/cutting_stage.h"
#include "engine/input_error.h"
#include "engine/mesh_check.h"
#include "engine/sim_state.h"
#include "fem/fem_stage.h"
#include "haptics/haptics_stage.h"
#include "metrics/metrics_stage.h"
#include "surface/surface_stage.h"

namespace serosa::app {
namespace {

using Json = nlohmann::json;
using Clock = std::chrono::steady_clock;

double ms_since(Clock::time_point t0) {
  return std::chrono::duration<double, std::milli>(Clock::now() - t0).count();
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

// Each placed ligature (clip or loop: when, by which tool, what it clamps, where it is now) and
// the clips each applier closed on no tissue and the loops cinched round none.
Json clips_json(const Scene& scene, const SimState& state,
                const std::map<int, std::string>& group_names) {
  Json placed = Json::array();
  for (const Clip& c : state.shared.clips) {
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
      dropped[scene.tools[i].name] = contact::clips_dropped(state, i);
    if (k == ToolKind::kStapler) refused[scene.tools[i].name] = contact::stapler_refused(state, i);
  }
  Json j = {{"placed", std::move(placed)}, {"dropped", std::move(dropped)}};
  if (!refused.empty()) j["refused"] = std::move(refused);  // fires on a ligature, per stapler
  return j;
}

StepDetail step_detail(const Runner& runner, const fem::FemStage* fem) {
  StepDetail d;
  d.fem_ms = 1e3 * runner.last_stage_s("fem");
  if (fem != nullptr) {
    const fem::StepStatus& st = fem->last_status();
    d.cg_iterations = st.iterations;
    d.factor_refresh = st.factor_refresh;
    d.factor_patch = st.factor_patch;
    d.factor_wait_ms = st.factor_wait_ms;
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

// The scene the options name, loaded after their outputs are checked (a run that could not write
// its results fails before anything is read).
Scene checked_scene(const HeadlessOptions& o) {
  (void)check_outputs(o);
  return load_scene(o.scene, o.overrides);
}

}  // namespace

Simulation::Simulation(const HeadlessOptions& options)
    : Simulation(checked_scene(options), options) {}

Simulation::Simulation(Scene scene, const HeadlessOptions& options, SimulationHooks hooks)
    : m_options(options),
      m_hooks(std::move(hooks)),
      m_final_format(check_outputs(options)),
      m_scene(std::move(scene)),
      m_wall0(Clock::now()) {
  if (options.tool_path) play_tool_path(m_scene, *options.tool_path);
  m_planned = steps_to_run(options, m_scene);
  m_initial = assemble_state(m_scene);
  m_python_poses.resize(m_scene.tools.size());
  for (std::size_t i = 0; i < m_scene.tools.size(); ++i)
    if (m_scene.tools[i].device.kind == DeviceKind::kPython)
      m_python_poses[i] = std::make_unique<Seqlock<ToolState>>(ToolState{});
  m_pipe = build();
  // Record: the last stage, after everything the step changed.
  if (options.record || options.scene_record)
    m_writer = record_run(m_pipe->comp, m_scene, options.record,
                          recording_header(m_scene, m_planned), m_hooks.run_name);
  if (!m_hooks.quiet)
    for (Effect e : m_pipe->comp.unavailable)
      spdlog::warn("effect '{}' is listed by {} but not implemented in this build: not simulated",
                   effect_name(e), m_scene.file.string());
  start_report();
  if (!m_hooks.quiet) m_warnings = selection_warnings(m_scene, m_pipe->assembled);
  // A path given in place of the scene's may outlast the steps the scene planned for its own.
  if (options.tool_path && !options.steps && !options.seconds) {
    const std::vector<RunWarning> cut = path_warnings(m_scene, *options.tool_path, m_planned);
    m_warnings.insert(m_warnings.end(), cut.begin(), cut.end());
  }
  print_warnings(m_warnings);  // before the run: an empty selection is known now
  if (options.frames) plan_pictures(*options.frames);
  const auto p0 = Clock::now();
  // Load time, not step time: the FEM's structure and first factor.
  m_pipe->comp.runner->prepare(m_pipe->assembled.state);
  m_prepare_ms = ms_since(p0);
  if (options.series) m_series.emplace(*options.series, m_scene);
  if (options.vtu_series) m_vtu.emplace(*options.vtu_series, options.vtu_every);
  if (m_vtu) m_vtu->add(m_pipe->assembled.state);
  m_paced = !m_hooks.caller_paces && m_pipe->comp.haptics && m_pipe->comp.haptics->driven_by_rig();
  m_step_ms.reserve(static_cast<std::size_t>(m_planned));  // no growth while the run steps
  m_details.reserve(static_cast<std::size_t>(m_planned));
}

Simulation::~Simulation() {
  // A run dropped without finish() (an exception, a Python object collected) still leaves a
  // readable recording behind.
  if (m_writer && !m_stopped) {
    try {
      m_writer->close(m_pipe->assembled.state.step);
    } catch (const std::exception& e) {
      spdlog::error("{}: {}", m_writer->path().string(), e.what());
    }
  }
}

std::unique_ptr<Simulation::Pipeline> Simulation::build() const {
  auto p = std::make_unique<Pipeline>();
  p->assembled = m_initial;
  ComposeOptions co;
  co.validate_cuts = m_options.validate_cuts;
  for (std::size_t i = 0; i < m_python_poses.size(); ++i)
    if (m_python_poses[i]) co.live_poses.push_back({i, m_python_poses[i].get()});
  if (m_hooks.tool_input) co.tool_input = m_hooks.tool_input();
  if (m_hooks.compose) m_hooks.compose(co);
  p->comp = compose(m_scene, p->assembled, std::move(co));
  if (m_hooks.extend) m_hooks.extend(*p->comp.runner);
  return p;
}

void Simulation::start_report() {
  Json& r = m_report;
  r["serosa"] = std::string(version_string());
  r["scene"] = m_scene.file.string();
  r["dt_s"] = m_scene.settings.dt_s;
  r["steps"] = m_planned;
  for (Effect e : m_pipe->comp.built) r["effects"]["simulated"].push_back(effect_name(e));
  for (Effect e : m_pipe->comp.folded) r["effects"]["folded"].push_back(effect_name(e));
  for (Effect e : m_pipe->comp.unavailable) r["effects"]["unavailable"].push_back(effect_name(e));
  r["mesh_initial"] = mesh_json(m_pipe->assembled.state.mesh);
  r["solver"] = solver_report(m_scene.solver);
  if (auto preset = preset_report(m_scene)) r["preset"] = std::move(*preset);
  r["fixed"] = fixed_json(m_pipe->assembled);
  r["provenance"] = provenance_json(m_scene, m_options.overrides, m_pipe->assembled);
}

nlohmann::json Simulation::picture_blocks() const {
  Json j = Json::object();
  for (const char* key : {"frames", "frames_camera", "frames_flat", "frames_blood"})
    if (m_report.contains(key)) j[key] = m_report[key];
  return j;
}

void Simulation::plan_pictures(const std::filesystem::path& folder) {
  m_pictures = std::make_unique<FramePictures>(folder, m_scene, m_pipe->assembled.state.mesh,
                                               m_pipe->assembled.group_names());
  m_pictures->set_endoscope(!m_options.fitted_camera);
  const int count = std::max(m_options.frame_count, 1);
  for (int k = 0; k < count; ++k)  // spread over the run, the first and last step included
    m_picture_steps.push_back(count == 1 ? m_planned : m_planned * k / std::max(count - 1, 1));
}

void Simulation::take_picture_if_due(std::int64_t step) {
  if (!m_pictures ||
      std::find(m_picture_steps.begin(), m_picture_steps.end(), step) == m_picture_steps.end())
    return;
  const auto r0 = Clock::now();
  ++m_rendered;
  char stem[32];
  std::snprintf(stem, sizeof stem, "step_%06lld", static_cast<long long>(step));
  for (const auto& png : m_pictures->take(m_pipe->assembled.state, stem))
    m_report["frames"].push_back(png.string());
  m_report["frames_camera"] = m_pictures->camera_used();
  m_report["frames_flat"].push_back(m_pictures->flat_fraction());
  m_report["frames_blood"].push_back(m_pictures->blood_fraction());
  m_render_s += 1e-3 * ms_since(r0);
}

void Simulation::step() {
  SimState& state = m_pipe->assembled.state;
  if (!m_step0) {
    m_step0 = Clock::now();
    take_picture_if_due(static_cast<std::int64_t>(state.step));
  }
  if (m_paced)
    std::this_thread::sleep_until(
        *m_step0 + std::chrono::duration_cast<Clock::duration>(std::chrono::duration<double>(
                       static_cast<double>(m_step_ms.size()) * m_scene.settings.dt_s)));
  const auto s0 = Clock::now();
  m_pipe->comp.runner->step(state);
  m_step_ms.push_back(ms_since(s0));
  m_details.push_back(step_detail(*m_pipe->comp.runner, m_pipe->comp.fem));
  if (m_series)
    m_series->add(state, m_step_ms.back(), m_details.back().fem_ms,
                  m_pipe->comp.fem ? m_pipe->comp.fem->last_status() : fem::StepStatus{});
  if (m_vtu) m_vtu->add(state);
  take_picture_if_due(static_cast<std::int64_t>(state.step));
}

void Simulation::set_tool(std::size_t tool, const ToolState& pose) {
  if (tool >= m_python_poses.size() || !m_python_poses[tool])
    throw std::invalid_argument(
        "tool " + (tool < m_scene.tools.size() ? "'" + m_scene.tools[tool].name + "'" : "#?") +
        " is not driven from Python (its device is not \"python\" in " + m_scene.file.string() +
        ")");
  ToolState t = pose;
  t.tick = ++m_pose_tick;
  t.time_s = m_pipe->assembled.state.time_s;
  m_python_poses[tool]->store(t);
}

std::optional<ToolState> Simulation::pose_set(std::size_t tool) const {
  if (tool >= m_python_poses.size() || !m_python_poses[tool]) return std::nullopt;
  const ToolState t = m_python_poses[tool]->load();
  return t.tick > 0 ? std::optional<ToolState>(t) : std::nullopt;
}

cutting::StrokeReport Simulation::cut(const cutting::ConvexPolygon& polygon) {
  if (!m_pipe->comp.cutting)
    throw std::invalid_argument(m_scene.file.string() +
                                " does not list the effect \"cutting\": nothing can cut");
  m_pipe->comp.cutting->queue_cut(polygon);
  step();
  const auto& done = m_pipe->comp.cutting->queued_cuts();
  return done.empty() ? cutting::StrokeReport{} : done.front();
}

std::vector<std::uint8_t> Simulation::snapshot() const {
  if (!m_pipe->assembled.state.events.cuts.empty())
    throw std::logic_error("a cut is in flight (this step cut): take one more step first");
  return m_pipe->comp.runner->snapshot(m_pipe->assembled.state);
}

void Simulation::restore(std::span<const std::uint8_t> bytes, const std::string& what) {
  if (m_writer)
    throw std::logic_error("this run records to " + m_writer->path().string() +
                           ": a restore would break the recording");
  std::unique_ptr<Pipeline> fresh = build();
  fresh->comp.runner->restore(bytes, fresh->assembled.state, what);  // throws: the run stays
  fresh->comp.runner->prepare(fresh->assembled.state);
  m_pipe = std::move(fresh);
  // The per-step timings follow the steps: those after the snapshot's are no longer this run's.
  m_step_ms.resize(m_pipe->assembled.state.step, 0.0);
  m_details.resize(m_pipe->assembled.state.step);
}

Json Simulation::stop() {
  Json j = Json::object();
  if (m_stopped) return j;
  m_stopped = true;
  if (m_pipe->comp.haptics) j["haptics"] = m_pipe->comp.haptics->telemetry_json();  // stops it
  if (m_writer) j["recording"] = close_recording(*m_writer, m_scene, m_pipe->assembled.state.step);
  return j;
}

void Simulation::reserve(std::int64_t steps) {
  m_step_ms.reserve(static_cast<std::size_t>(std::max<std::int64_t>(steps, 0)));
  m_details.reserve(static_cast<std::size_t>(std::max<std::int64_t>(steps, 0)));
}

void Simulation::reset() {
  if (m_writer)
    throw std::logic_error("this run records to " + m_writer->path().string() +
                           ": a reset would break the recording");
  std::unique_ptr<Pipeline> fresh = build();
  fresh->comp.runner->prepare(fresh->assembled.state);
  m_pipe = std::move(fresh);
  m_step_ms.clear();
  m_details.clear();
}

void Simulation::add_run_blocks(Json& report) const {
  const SimState& state = m_pipe->assembled.state;
  report["steps_taken"] = state.step;
  report["paced_to_real_time"] = m_paced;
  for (const StageTiming& t : m_pipe->comp.runner->timings())
    report["time_per_stage_ms"][t.name] =
        t.calls ? 1e3 * t.total_s / static_cast<double>(t.calls) : 0.0;
  // Rendering is not a solver stage headless: ms per picture step, when pictures were drawn.
  if (m_rendered > 0)
    report["time_per_stage_ms"]["render"] = 1e3 * m_render_s / static_cast<double>(m_rendered);
  report["simulated_time_s"] = state.time_s;
  report["wall_time_s"] = 1e-3 * ms_since(m_wall0);
  report["stepping_time_s"] = m_step0 ? 1e-3 * ms_since(*m_step0) : 0.0;
  report["step_time_ms"] = step_time_json(m_step_ms, m_details);
  report["prepare_ms"] = m_prepare_ms;  // load time before the first step (Runner::prepare)
  // Simulated over wall time of the solver steps: >= 1 runs ahead of the clock.
  double stepped_s = 0.0;
  for (double ms : m_step_ms) stepped_s += 1e-3 * ms;
  report["real_time_factor"] = stepped_s > 0.0 ? state.time_s / stepped_s : 0.0;
  report["mesh_final"] = mesh_json(state.mesh);
  if (m_options.positions) {
    // For a golden: where every node ended, and which binary put it there (the state hash is
    // exact only for the same binary and thread count).
    Json nodes = Json::array();
    // To the nanometre: a golden compares them to 10 um, and the file stays small.
    const auto nm = [](double v) { return std::round(v * 1e9) / 1e9; };
    for (const Vec3& x : state.mesh.x) nodes.push_back({nm(x.x()), nm(x.y()), nm(x.z())});
    report["nodes_final_m"] = std::move(nodes);
    report["binary_id"] = binary_id();
  }
  for (const Blood& b : state.shared.blood)
    report["bleeding"].push_back({{"since_s", b.since_s},
                                  {"shed_m3", b.shed_m3},
                                  {"pool_radius_m", b.pool_radius_m},
                                  {"flowing", b.pulse > 0.0}});
  report["state_hash"] = hash_hex(state_hash(state));
  if (m_pipe->comp.cutting) {
    report["cutting"] = cutting_json(m_pipe->comp);
    // The step each stroke was cut in, and the next (whose FEM takes the new tets), against dt;
    // kept out of "cutting", which a replay reproduces exactly.
    Json cut_steps = Json::array();
    for (const cutting::StrokeReport& r : m_pipe->comp.cutting->stats().stroke_reports) {
      const auto at = static_cast<std::size_t>(r.last_step);
      if (at >= m_step_ms.size()) continue;
      cut_steps.push_back({{"step", r.last_step},
                           {"ms", m_step_ms[at]},
                           {"next_ms", at + 1 < m_step_ms.size() ? m_step_ms[at + 1] : 0.0}});
    }
    report["cut_steps"] = std::move(cut_steps);
  }
  add_metrics_blocks(report, m_scene, m_pipe->comp.metrics, state.mesh,
                     m_pipe->assembled.group_names());
  add_stage_blocks(report);
}

void Simulation::add_stage_blocks(Json& report) const {
  const SimState& state = m_pipe->assembled.state;
  if (m_pipe->comp.contact) {
    const auto held = contact::grasped_counts(state);
    for (std::size_t i = 0; i < m_scene.tools.size() && i < held.size(); ++i)
      if (m_scene.tools[i].kind == ToolKind::kGrasper)
        report["contact"]["held_nodes"][m_scene.tools[i].name] = held[i];
  }
  if (m_pipe->comp.clips)
    report["clips"] = clips_json(m_scene, state, m_pipe->assembled.group_names());
  if (m_pipe->comp.surface) {
    const auto& ss = m_pipe->comp.surface->stats();
    report["surface"] = {
        {"faces", state.shared.surface.num_faces()},
        {"rebuilds", ss.rebuilds},
        {"updates", ss.updates},
        {"failed_updates", ss.failed_updates},
        {"backend", m_pipe->comp.surface->backend() == surface::Backend::kCuda ? "cuda" : "cpu"}};
  }
  std::vector<RunWarning> warnings = m_warnings;
  if (m_pipe->comp.fem) {
    const auto& st = m_pipe->comp.fem->stats();
    const auto& fem = *m_pipe->comp.fem;
    report["fem"] = {{"steps", st.steps},
                     {"not_converged", st.not_converged},
                     {"factor_refreshes", st.factor_refreshes},
                     {"factor_patches", st.factor_patches},
                     {"rejected", st.rejected},
                     {"energy_gains", st.energy_gains},
                     {"energy_gains_after_capped_solve", st.energy_gains_after_capped_solve},
                     {"energy_removed_j", st.energy_removed_j},
                     {"peak_energy_j", st.peak_energy_j},
                     {"last_iterations", fem.last_status().iterations},
                     {"last_residual", fem.last_status().residual},
                     {"debris_tets", fem.integrator().elements().debris_tets},
                     {"debris_volume_m3", fem.integrator().elements().debris_volume_m3}};
    const std::vector<RunWarning> solver = solver_warnings(m_scene.solver, st);
    warnings.insert(warnings.end(), solver.begin(), solver.end());
  }
  report["warnings"] = warnings_json(warnings);
}

Json Simulation::report() const {
  Json report = m_report;
  add_run_blocks(report);
  return report;
}

Json Simulation::finish(bool interrupted) {
  if (m_finished) throw std::logic_error("the run has already finished");
  m_finished = true;
  SimState& state = m_pipe->assembled.state;
  if (!m_step0) take_picture_if_due(static_cast<std::int64_t>(state.step));
  Json report = m_report;
  report.update(stop());
  add_run_blocks(report);
  if (interrupted) report["interrupted"] = true;
  if (m_pipe->comp.fem) print_warnings(solver_warnings(m_scene.solver, m_pipe->comp.fem->stats()));
  if (m_options.export_final) {
    write_mesh_output(*m_options.export_final, *m_final_format, state.mesh,
                      m_pipe->assembled.group_names());
    report["export_final"] = m_options.export_final->string();
  }
  if (m_series) {
    m_series->close();
    report["series"] = m_options.series->string();
  }
  if (m_vtu)
    report["vtu_series"] = {{"folder", m_options.vtu_series->string()}, {"files", m_vtu->close()}};
  if (m_options.report) {
    std::ofstream out(*m_options.report);
    out << report.dump(2) << '\n';
    if (!out) throw std::runtime_error("cannot write report " + m_options.report->string());
  }
  return report;
}

}  // namespace serosa::app
