#include "app/compose.h"

#include <spdlog/spdlog.h>

#include <algorithm>
#include <cmath>

#include "contact/support_stage.h"
#include "cutting/cutting_stage.h"
#include "cutting/smoke_stage.h"
#include "engine/input_error.h"
#include "engine/script_tool_stage.h"
#include "engine/sim_state.h"
#include "engine/tissue_stress.h"
#include "fem/fem_stage.h"
#include "haptics/haptics_stage.h"
#include "metrics/bleeding_stage.h"
#include "metrics/metrics_stage.h"
#include "surface/surface_stage.h"

namespace serosa::app {
fem::SolverKind to_fem(SolverKind k) {
  switch (k) {
    case SolverKind::kPcg:
      return fem::SolverKind::pcg;
    case SolverKind::kCholmod:
      return fem::SolverKind::cholmod;
    case SolverKind::kPcgCholmod:
      return fem::SolverKind::pcg_cholmod;
    case SolverKind::kPcgLagged:
      return fem::SolverKind::pcg_lagged;
  }
  return fem::SolverKind::pcg;
}

namespace {

fem::FemMaterial to_fem(const Material& m) {
  fem::FemMaterial f;
  f.young_pa = m.young_pa;
  f.poisson = m.poisson;
  f.density_kgpm3 = m.density_kgpm3;
  f.damping_mass = m.damping.mass_per_s;
  f.damping_stiffness = m.damping.stiffness_s;
  return f;
}

}  // namespace

fem::FemConfig fem_config(const Scene& scene, const AssembledScene& assembled) {
  fem::FemConfig c;
  for (const auto& [g, info] : assembled.groups)
    c.materials[static_cast<std::uint16_t>(g)] = to_fem(assembled.material(scene, g));
  c.solver.kind = to_fem(scene.solver.kind);
  c.solver.tolerance = scene.solver.tolerance;
  c.solver.max_iterations = scene.solver.max_iterations;
  c.solver.refresh_iterations = scene.solver.refresh_iterations;
  c.solver.factor_lag_steps = scene.solver.factor_lag_steps;
  c.solver.patch_after_cut = scene.solver.patch_after_cut;
  c.solver.urgent_lag_steps = scene.solver.urgent_lag_steps;
  c.solver.cut_lag_steps = scene.solver.cut_lag_steps;
  c.solver.misfit_rad = scene.solver.misfit_rad;
  c.solver.patch_rings = scene.solver.patch_rings;
  c.solver.threads = scene.solver.threads;
  // pcg-lagged needs 1-3 CG iterations a step: filling the assembled blocks for so few products
  // cost more than applying A per tet, so it fills them only on the steps that factor
  // (docs/BENCHMARKS.md "Real time": 25 % less FEM time a step on the default scene).
  c.solver.matrix_free = c.solver.kind == fem::SolverKind::pcg_lagged;
  // A capped CG's energy gains are taken back out (the grasper, the one stage that moves nodes
  // between steps, says so in SimState::events.nodes_moved).
  c.solver.remove_energy_gain = true;
  c.gravity_on = scene.settings.has(Effect::kGravity);
  // Plastic flow with each group's material parameters (organ-wide, or the group's override).
  c.plasticity.on = scene.settings.has(Effect::kPlasticity);
  for (const auto& [g, info] : assembled.groups) {
    const PlasticityParams& p = assembled.material(scene, g).plasticity;
    c.plasticity_groups[static_cast<std::uint16_t>(g)] = {true, p.yield, p.creep_per_s, p.max};
  }
  c.gravity_mps2 = scene.settings.gravity_mps2;
  return c;
}

LameTable lame_table(const Scene& scene, const AssembledScene& assembled) {
  LameTable t;
  for (const auto& [g, info] : assembled.groups)
    t.groups[static_cast<std::uint16_t>(g)] = lame(assembled.material(scene, g));
  if (!scene.organs.empty()) t.fallback = lame(scene.organs.front().material);
  return t;
}

void mark_recording(Composition& c) {
  c.folded.erase(std::remove(c.folded.begin(), c.folded.end(), Effect::kRecord), c.folded.end());
  c.built.push_back(Effect::kRecord);
}

std::unique_ptr<recording::RecordingWriter> record_run(
    Composition& c, const Scene& scene, const std::optional<std::filesystem::path>& path,
    const recording::Header& header, const char* run) {
  const std::optional<std::filesystem::path> file = path ? path : scene.record.path;
  if (!file) {
    if (scene.settings.has(Effect::kRecord))
      spdlog::info(
          "{} lists 'record' and gives no file: this {} is not recorded (--record FILE "
          "or [record] path)",
          scene.file.string(), run);
    return nullptr;
  }
  std::unique_ptr<recording::RecordingWriter> writer;
  try {
    writer = std::make_unique<recording::RecordingWriter>(*file, header);
  } catch (const std::exception& e) {
    throw InputError(file->string(), 0, e.what(), "a writable path");
  }
  c.runner->add(Slot::record, std::make_unique<RecordStage>(writer.get(), scene.record.hash_every));
  const auto every =
      static_cast<std::uint64_t>(std::llround(scene.record.snapshot_every_s / scene.settings.dt_s));
  c.runner->record_snapshots(*writer, every);
  mark_recording(c);
  return writer;
}

Composition compose(const Scene& scene, const AssembledScene& assembled, ComposeOptions options) {
  Composition c;
  c.runner = std::make_unique<Runner>(scene.settings.dt_s);
  const auto listed = [&](Effect e) { return scene.settings.has(e); };

  // Construct only what is listed; then hand the stages to the runner in pipeline order:
  // tools -> contact -> FEM -> cuts -> surface -> metrics (record is added by the caller).
  std::unique_ptr<fem::FemStage> fem_stage;
  if (listed(Effect::kFem))
    fem_stage = std::make_unique<fem::FemStage>(fem_config(scene, assembled));
  // Contact reads the surface the surface stage keeps: it brings one along when not listed.
  std::unique_ptr<SurfaceStage> surface_stage;
  if (listed(Effect::kSurface) || listed(Effect::kContact))
    surface_stage = std::make_unique<SurfaceStage>(assembled.state.mesh);
  std::unique_ptr<CuttingStage> cutting_stage;
  if (listed(Effect::kCutting) || listed(Effect::kCautery)) {  // scissors and hooks divide
    CuttingStageOptions co;
    co.scissors = listed(Effect::kCutting);
    co.hooks = listed(Effect::kCautery);
    co.staplers = listed(Effect::kCutting) && listed(Effect::kClips);  // its knife and lines
    co.validate = options.validate_cuts || kCheckEveryCutByDefault;    // always in debug builds
    cutting_stage = std::make_unique<CuttingStage>(scene, co);
  }
  // The haptic loop renders the contact stage's planes (not in a replay: no loop runs there).
  const bool haptic_loop = listed(Effect::kHaptics) && !options.tool_input;
  // Metrics measure the tools and the cuts: a scene with no tool has nothing to score.
  std::unique_ptr<MetricsStage> metrics_stage;
  if (fem_stage && !scene.tools.empty())
    metrics_stage = std::make_unique<MetricsStage>(scene, lame_table(scene, assembled), 1,
                                                   assembled.group_names());
  std::unique_ptr<ToolContactStage> contact_stage;
  if (listed(Effect::kContact)) {
    // The metrics count closing scissors' load on the tissue as their force.
    const contact::ContactOutputs outputs{haptic_loop, metrics_stage != nullptr};
    contact_stage =
        std::make_unique<ToolContactStage>(scene, lame_table(scene, assembled), outputs);
  }

  // take tool states
  if (options.tool_input) {
    c.tool_input = options.tool_input.get();
    c.runner->add(Slot::tools, std::move(options.tool_input));
  } else if (std::any_of(scene.tools.begin(), scene.tools.end(),
                         [](const Tool& t) { return t.device.kind == DeviceKind::kScript; })) {
    auto tools = std::make_unique<ScriptToolStage>(scene);
    c.tools = tools.get();
    c.runner->add(Slot::tools, std::move(tools));
  }
  if (!options.live_poses.empty())
    c.runner->add(Slot::tools, std::make_unique<LivePoseStage>(std::move(options.live_poses)));
  // the haptic loop's handles override their scripted tools (a replay feeds recorded inputs)
  if (haptic_loop) {
    HapticsStageOptions ho;
    ho.realtime = options.realtime_haptics;
    ho.rest_pose = options.mouse_rest_pose;
    const TetMesh& mesh = assembled.state.mesh;
    if (!mesh.x.empty()) {
      Vec3 sum = Vec3::Zero();
      for (const Vec3& x : mesh.x) sum += x;
      ho.aim_m = sum / static_cast<double>(mesh.x.size());
    }
    auto haptics_stage = std::make_unique<HapticsStage>(scene, ho);
    c.haptics = haptics_stage.get();
    c.runner->add(Slot::haptics, std::move(haptics_stage));
    c.built.push_back(Effect::kHaptics);
  }
  // contact, then the clips (they hold what they clamp over whatever touched it)
  if (contact_stage) {
    c.contact = contact_stage.get();
    c.runner->add(Slot::contact, std::move(contact_stage));
    c.built.push_back(Effect::kContact);
  }
  if (listed(Effect::kClips) || listed(Effect::kLoops)) {  // ligatures: clips and loops
    auto clip_stage = std::make_unique<ClipStage>(scene);
    c.clips = clip_stage.get();
    c.runner->add(Slot::contact, std::move(clip_stage));
    if (listed(Effect::kClips)) c.built.push_back(Effect::kClips);
    if (listed(Effect::kLoops)) c.built.push_back(Effect::kLoops);
  }
  // the supports the organs rest on (their forces join the contact stage's)
  if (listed(Effect::kSupports) && fem_stage) {
    c.runner->add(Slot::contact,
                  std::make_unique<contact::SupportStage>(scene, c.contact == nullptr));
    c.built.push_back(Effect::kSupports);
  }
  // FEM (gravity is one of its terms)
  if (fem_stage) {
    c.fem = fem_stage.get();
    c.runner->add(Slot::fem, std::move(fem_stage));
    c.built.push_back(Effect::kFem);
    // Gravity and plastic flow are terms of the FEM stage: simulated when listed.
    if (listed(Effect::kGravity)) c.built.push_back(Effect::kGravity);
    if (listed(Effect::kPlasticity)) c.built.push_back(Effect::kPlasticity);
  }
  // cuts (between FEM steps), then the surface they change
  if (cutting_stage) {
    c.cutting = cutting_stage.get();
    c.runner->add(Slot::cutting, std::move(cutting_stage));
    if (listed(Effect::kCutting)) c.built.push_back(Effect::kCutting);
    if (listed(Effect::kCautery)) c.built.push_back(Effect::kCautery);
    // the smoke of what the hooks coagulated (after them: they mark it)
    if (listed(Effect::kSmoke)) {
      c.runner->add(Slot::cutting, std::make_unique<cutting::SmokeStage>(scene));
      c.built.push_back(Effect::kSmoke);
    }
  }
  if (surface_stage) {
    c.surface = surface_stage.get();
    c.runner->add(Slot::surface, std::move(surface_stage));
    if (listed(Effect::kSurface)) c.built.push_back(Effect::kSurface);
  }
  if (metrics_stage) {
    c.metrics = metrics_stage.get();
    c.runner->add(Slot::metrics, std::move(metrics_stage));
    // the blood of what the metrics found cut (after them: they find it)
    if (listed(Effect::kBleeding)) {
      c.runner->add(Slot::metrics, std::make_unique<metrics::BleedingStage>(scene));
      c.built.push_back(Effect::kBleeding);
    }
  }
  if (listed(Effect::kRender)) c.folded.push_back(Effect::kRender);
  if (listed(Effect::kRecord)) c.folded.push_back(Effect::kRecord);

  // Everything else the scene lists waits for its stage to land.
  for (Effect e : scene.settings.effects) {
    const bool handled = std::find(c.built.begin(), c.built.end(), e) != c.built.end() ||
                         std::find(c.folded.begin(), c.folded.end(), e) != c.folded.end();
    if (!handled) c.unavailable.push_back(e);
  }
  return c;
}

}  // namespace serosa::app
