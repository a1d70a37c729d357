// `serosa bench scenes`: the shipped appendectomy scenes as the trainee runs them, every stage of
// the step included. For each solver setting and dt: the real-time factor (simulated time over
// the wall time of the steps), the step-time distribution (p50, p99, max, through the cut), and
// the accuracy against the exact solve of the same scene (CHOLMOD, the scene's dt): the largest
// max_i |x_i - x_exact_i| over the steps before the first cut, relative to the largest
// displacement max_i |x_exact_i - x_exact_i(0)| reached so far (steps before it reaches 0.1 mm
// are not judged: there is nothing to be relative to). A setting with a
// coarser dt is compared at the reference's steps of the same time. The scenes' presets are chosen
// from these curves.
#include <algorithm>
#include <chrono>
#include <cmath>
#include <string>
#include <vector>

#include "app/assemble_state.h"
#include "app/compose.h"
#include "app/simulation.h"
#include "bench/suite/bench_parts.h"
#include "engine/scene/scene.h"
#include "engine/sim_state.h"

namespace serosa::bench {

using namespace serosa::app;  // the driver and the composition the scenes run on

namespace {

struct Setting {
  std::string label;
  SolverKind kind = SolverKind::kPcgLagged;
  double tolerance = 1e-4;
  int max_iterations = 200;
  int dt_ratio = 1;             // dt = dt_ratio x the scene's dt
  bool patch_after_cut = true;  // pcg-lagged after a cut: patch (true) or factor at once
};

struct Trajectory {
  std::vector<std::vector<Vec3>> x;  // (steps before the first cut) x (n) positions, m
  std::vector<double> step_ms;       // (steps) wall time of each step, ms
  double simulated_s = 0.0;
};

// Runs `scene` with `s` for `seconds` of simulated time, keeping positions until the topology
// first changes.
Trajectory run(const Scene& base, const Setting& s, double seconds) {
  Scene scene = base;
  scene.solver.kind = s.kind;
  scene.solver.tolerance = s.tolerance;
  scene.solver.max_iterations = s.max_iterations;
  scene.solver.patch_after_cut = s.patch_after_cut;
  scene.settings.dt_s = base.settings.dt_s * s.dt_ratio;
  HeadlessOptions o;  // the headless driver: the same load, compose and prepare as the session's
  o.progress = false;
  o.scene_record = false;
  const auto steps = static_cast<std::int64_t>(std::llround(seconds / scene.settings.dt_s));
  o.steps = steps;
  Simulation sim(std::move(scene), o);
  const SimState& state = sim.state();
  const std::uint64_t version0 = state.mesh.topology_version;
  Trajectory t;
  t.x.push_back(state.mesh.x);
  for (std::int64_t k = 0; k < steps; ++k) {
    sim.step();
    if (state.mesh.topology_version == version0) t.x.push_back(state.mesh.x);
  }
  t.step_ms = sim.step_ms();
  t.simulated_s = state.time_s;
  return t;
}

// The largest relative error of `c` against the reference `ref` over the steps both have before
// the first cut (c's step k is ref's step k * ratio), from the step the reference's largest
// displacement first reaches `judged_from_m` on.
double relative_error(const Trajectory& c, const Trajectory& ref, int ratio, double judged_from_m) {
  double worst = 0.0, reach = 0.0;
  for (std::size_t k = 1; k < c.x.size(); ++k) {
    const std::size_t kr = k * static_cast<std::size_t>(ratio);
    if (kr >= ref.x.size()) break;
    double diff = 0.0;
    for (std::size_t i = 0; i < ref.x[kr].size(); ++i) {
      reach = std::max(reach, (ref.x[kr][i] - ref.x[0][i]).norm());
      diff = std::max(diff, (c.x[k][i] - ref.x[kr][i]).norm());
    }
    if (reach >= judged_from_m) worst = std::max(worst, diff / reach);
  }
  return worst;
}

double quantile(std::vector<double> v, double q) {
  std::sort(v.begin(), v.end());
  return v[std::min(v.size() - 1, static_cast<std::size_t>(q * static_cast<double>(v.size())))];
}

// One scene's curves: `reference` stands for the exact solve (CHOLMOD; on the fine mesh, where a
// direct factorization a step takes seconds, pcg-lagged converged to 1e-8).
// judged_from_m: the displacement before which no error is judged (nothing to be relative to).
void scene_curves(const BenchOptions& options, const std::string& file, const std::string& tag,
                  double seconds, const Setting& reference, const std::vector<Setting>& settings,
                  double judged_from_m, PartResult& result) {
  const Scene scene = load_scene(options.assets_dir / ".." / "config" / file);
  const Trajectory ref = run(scene, reference, seconds);
  Table t{"scene_" + tag,
          {"tolerance", "dt_s", "real_time_factor", "step_ms_p50", "step_ms_p99", "step_ms_max",
           "rel_error"},
          {},
          {}};
  const auto add = [&](const std::string& label, const Setting& s, const Trajectory& tr) {
    double wall_s = 0.0;
    for (double ms : tr.step_ms) wall_s += 1e-3 * ms;
    t.add(label, {s.tolerance, scene.settings.dt_s * s.dt_ratio, tr.simulated_s / wall_s,
                  quantile(tr.step_ms, 0.5), quantile(tr.step_ms, 0.99), quantile(tr.step_ms, 1.0),
                  relative_error(tr, ref, s.dt_ratio, judged_from_m)});
  };
  add(reference.label, reference, ref);
  Table sweep{"scene_" + tag + "_lagged_tolerance", t.columns, {}, {}};
  for (const Setting& s : settings) {
    add(s.label, s, run(scene, s, seconds));
    if (s.kind == SolverKind::kPcgLagged && s.dt_ratio == 1 && s.patch_after_cut) {
      sweep.settings.push_back(t.settings.back());
      sweep.rows.push_back(t.rows.back());
    }
  }
  Plot p{"scene_" + tag,
         "The " + tag + " scene (" + file + ", " + std::to_string(scene.tools.size()) +
             " tools), " + std::to_string(static_cast<int>(seconds * 1000)) +
             " ms of its procedure: real-time factor against accuracy",
         "max position error / max displacement (before the cut)",
         "real-time factor (simulated / wall)",
         true,
         true,
         {{t.name, "rel_error", "real_time_factor", "solver setting, dt", true, true}}};
  result.plots.push_back(std::move(p));
  result.checks.push_back({sweep.name, "tolerance", "rel_error", Direction::increasing, 0.5, 1e-7,
                           "pcg-lagged: the error falls as the tolerance tightens"});
  for (std::size_t r = 0; r < t.rows.size(); ++r)
    result.notes.push_back(t.name + ": " + t.settings[r] + ": real-time factor " +
                           fmt_double("%.2f", t.rows[r][t.column("real_time_factor")]) +
                           ", step p50/p99/max " +
                           fmt_double("%.2f", t.rows[r][t.column("step_ms_p50")]) + "/" +
                           fmt_double("%.2f", t.rows[r][t.column("step_ms_p99")]) + "/" +
                           fmt_double("%.2f", t.rows[r][t.column("step_ms_max")]) + " ms, error " +
                           fmt_double("%.1e", t.rows[r][t.column("rel_error")]));
  result.tables.push_back(std::move(t));
  result.tables.push_back(std::move(sweep));
}

}  // namespace

PartResult run_scenes_part(const BenchOptions& options) {
  PartResult result;
  // The whole procedure (5 s, the transection included) in full; quick: up to the grasp (2.2 s),
  // the first time the tissue moves.
  const Setting exact{"cholmod (exact)", SolverKind::kCholmod, 1e-6, 1, 1};
  if (options.quick) {
    scene_curves(options, "appendectomy.toml", "appendectomy", 2.2, exact,
                 {{"pcg-lagged 1e-4", SolverKind::kPcgLagged, 1e-4, 200, 1},
                  {"pcg-lagged 1e-6", SolverKind::kPcgLagged, 1e-6, 200, 1}},
                 1e-4, result);
    return result;
  }
  scene_curves(
      options, "appendectomy.toml", "appendectomy", 5.0, exact,
      {{"cg jacobi 1e-4 cap 200", SolverKind::kPcg, 1e-4, 200, 1},
       {"pcg-cholmod 1e-4", SolverKind::kPcgCholmod, 1e-4, 200, 1},
       {"pcg-lagged 1e-2", SolverKind::kPcgLagged, 1e-2, 200, 1},
       {"pcg-lagged 1e-3", SolverKind::kPcgLagged, 1e-3, 200, 1},
       {"pcg-lagged 1e-3, factor after the cut", SolverKind::kPcgLagged, 1e-3, 200, 1, false},
       {"pcg-lagged 1e-4", SolverKind::kPcgLagged, 1e-4, 200, 1},
       {"pcg-lagged 1e-6", SolverKind::kPcgLagged, 1e-6, 200, 1},
       {"pcg-lagged 1e-4 dt x2", SolverKind::kPcgLagged, 1e-4, 200, 2},
       {"pcg-lagged 1e-4 dt x4", SolverKind::kPcgLagged, 1e-4, 200, 4}},
      1e-4, result);
  // The same procedure on the fine mesh, its first 3 s (the grasp, the lift and the clip; a
  // factorization takes a second there, so the exact solve a step is out of reach: the reference
  // is pcg-lagged converged to 1e-8).
  scene_curves(options, "appendectomy_fine.toml", "appendectomy_fine", 3.0,
               {"pcg-lagged 1e-8 (reference)", SolverKind::kPcgLagged, 1e-8, 500, 1},
               {{"pcg-lagged 1e-2", SolverKind::kPcgLagged, 1e-2, 200, 1},
                {"pcg-lagged 1e-3", SolverKind::kPcgLagged, 1e-3, 200, 1},
                {"pcg-lagged 1e-4", SolverKind::kPcgLagged, 1e-4, 200, 1},
                {"pcg-lagged 1e-3 dt x2", SolverKind::kPcgLagged, 1e-3, 200, 2}},
               1e-4, result);
  return result;
}

}  // namespace serosa::bench
