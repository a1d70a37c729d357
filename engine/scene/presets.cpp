#include "engine/scene/presets.h"

#include <algorithm>

namespace serosa {
namespace {

// docs/plots/bench_fem_cg_cap.csv, bench_fem_cg_tolerance.csv, bench_fem_cholmod_pcg_cap.csv and
// bench_fem_cholmod.csv: `serosa bench fem` (full) on the 19k-tet gmsh SOFA box
// (config/sofa_box19k.toml), 100 steps of 0.01 s, 2026-11-23 (docs/BENCHMARKS.md "serosa bench").
// tests/engine/test_presets.cpp compares these rows with those files: after a new bench run,
// copy its CSVs to docs/plots/ and these rows from them.
constexpr SolverCurvePoint kSolverCurve[] = {
    {"cap 5", SolverKind::kPcg, 0.0, 5, 0.971135255, 24.6552265},
    {"cap 10", SolverKind::kPcg, 0.0, 10, 0.887057901, 24.8913182},
    {"cap 20", SolverKind::kPcg, 0.0, 20, 0.501488871, 33.4415498},
    {"cap 35", SolverKind::kPcg, 0.0, 35, 0.0840517743, 39.8378717},
    {"cap 50", SolverKind::kPcg, 0.0, 50, 0.0284697376, 42.5528178},
    {"cap 75", SolverKind::kPcg, 0.0, 75, 0.00588893132, 54.7804516},
    {"cap 100", SolverKind::kPcg, 0.0, 100, 0.00074203378, 65.8667958},
    {"cap 150", SolverKind::kPcg, 0.0, 150, 0.000195835236, 87.2146276},
    {"cap 200", SolverKind::kPcg, 0.0, 200, 1.82337968e-05, 105.680555},
    {"tol 1e-01", SolverKind::kPcg, 0.1, 100000, 0.104130964, 44.38767},
    {"tol 1e-02", SolverKind::kPcg, 0.01, 100000, 0.00483453742, 56.6223694},
    {"tol 1e-03", SolverKind::kPcg, 0.001, 100000, 0.000177278513, 83.1566606},
    {"tol 1e-04", SolverKind::kPcg, 0.0001, 100000, 4.6305177e-06, 107.287077},
    {"tol 1e-05", SolverKind::kPcg, 1e-05, 100000, 2.26506551e-07, 144.097277},
    {"tol 1e-06", SolverKind::kPcg, 1e-06, 100000, 3.21285864e-08, 169.618526},
    {"tol 1e-07", SolverKind::kPcg, 1e-07, 100000, 7.94236998e-09, 227.242337},
    {"tol 1e-08", SolverKind::kPcg, 1e-08, 100000, 1.89313328e-09, 239.723845},
    {"pcg-cholmod cap 2", SolverKind::kPcgCholmod, 0.0, 2, 0.302651274, 83.2411141},
    {"pcg-cholmod cap 5", SolverKind::kPcgCholmod, 0.0, 5, 0.00564403032, 146.918364},
    {"pcg-cholmod cap 10", SolverKind::kPcgCholmod, 0.0, 10, 0.000338986851, 210.67537},
    {"pcg-cholmod cap 20", SolverKind::kPcgCholmod, 0.0, 20, 9.59035121e-06, 377.976265},
    {"pcg-cholmod cap 50", SolverKind::kPcgCholmod, 0.0, 50, 3.38991242e-09, 1000.0499},
    {"cholmod", SolverKind::kCholmod, 0.0, 1, 0, 966.144431},
};

// docs/plots/bench_tessellation_sphere.csv: `serosa bench tessellation`, the once-subdivided
// icosahedron (80 triangles) drawn at each Phong level against the unit sphere (llvmpipe).
constexpr TessellationCurvePoint kTessellationCurve[] = {
    {1, 0.0269923448, 10.0000557}, {2, 0.00774036776, 23.160153}, {3, 0.0118722228, 17.9916046},
    {4, 0.0139017086, 31.406729},  {5, 0.0148377016, 46.3634917}, {6, 0.0153451903, 63.6568375},
};

}  // namespace

std::span<const SolverCurvePoint> solver_curve() noexcept { return kSolverCurve; }
std::span<const TessellationCurvePoint> tessellation_curve() noexcept { return kTessellationCurve; }

double quality_accuracy_target(Quality q) noexcept {
  switch (q) {
    case Quality::kFast:
      return 0.05;  // 5 %: past the knee of the CG-cap curve (50 % at cap 20, 2.8 % at cap 50)
    case Quality::kBalanced:
      return 0.01;  // 1 %: the error at which the 19k box must still run >= 20 steps/s
    case Quality::kAccurate:
      return 1e-4;  // 0.01 %: indistinguishable from the converged solution on screen
  }
  return 0.01;
}

double quality_surface_target(Quality q) noexcept {
  switch (q) {
    case Quality::kFast:
      return 1.0;  // anything: flat triangles are the cheapest
    case Quality::kBalanced:
    case Quality::kAccurate:
      return 0.01;  // within 1 % of the radius of curvature
  }
  return 1.0;
}

PresetChoice choose_preset(double target, std::optional<Quality> quality) {
  PresetChoice c;
  c.target = target;
  const SolverCurvePoint* best = &kSolverCurve[0];
  for (const SolverCurvePoint& p : kSolverCurve) {
    if (p.rel_error <= target && (!c.target_met || p.ms_per_step < c.solver->ms_per_step)) {
      c.solver = &p;
      c.target_met = true;
    }
    if (p.rel_error < best->rel_error) best = &p;
  }
  if (!c.target_met) c.solver = best;
  if (quality) {
    const double surface = quality_surface_target(*quality);
    const TessellationCurvePoint* tess = nullptr;
    const TessellationCurvePoint* closest = &kTessellationCurve[0];
    for (const TessellationCurvePoint& p : kTessellationCurve) {
      if (p.mean_rel_distance <= surface && (!tess || p.frame_ms < tess->frame_ms)) tess = &p;
      if (p.mean_rel_distance < closest->mean_rel_distance) closest = &p;
    }
    c.tessellation = tess ? tess : closest;
  }
  return c;
}

std::optional<PresetChoice> scene_preset(const SceneSettings& settings) {
  if (!settings.accuracy_target) return std::nullopt;
  return choose_preset(*settings.accuracy_target, settings.quality);
}

void apply_preset(const PresetChoice& choice, SolverSettings& solver, RenderSettings& render) {
  solver.kind = choice.solver->kind;
  solver.tolerance = std::max(choice.solver->tolerance, 1e-10);
  solver.max_iterations = choice.solver->max_iterations;
  if (choice.tessellation) render.tessellation = choice.tessellation->level;
}

}  // namespace serosa
