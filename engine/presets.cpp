#include "engine/presets.h"

#include <algorithm>

namespace serosa {
namespace {

// docs/plots/fem_accuracy.csv: bench/fem BM_Accuracy on the 17,496-tet structured SOFA box,
// 100 steps of 0.01 s, 2026-11-23 (docs/BENCHMARKS.md "FEM"). tests/engine/test_presets.cpp
// compares these rows with that file.
constexpr SolverCurvePoint kSolverCurve[] = {
    {"cap5", SolverKind::kPcg, 0.0, 5, 0.95, 4.7},
    {"cap10", SolverKind::kPcg, 0.0, 10, 0.86, 5.0},
    {"cap20", SolverKind::kPcg, 0.0, 20, 0.49, 6.4},
    {"cap50", SolverKind::kPcg, 0.0, 50, 0.028, 9.5},
    {"cap100", SolverKind::kPcg, 0.0, 100, 0.00099, 15.2},
    {"cap200", SolverKind::kPcg, 0.0, 200, 1.6e-5, 27.5},
    {"tol1e-1", SolverKind::kPcg, 1e-1, 1000, 0.15, 8.4},
    {"tol1e-2", SolverKind::kPcg, 1e-2, 1000, 0.0046, 15.5},
    {"tol1e-3", SolverKind::kPcg, 1e-3, 1000, 9e-5, 24.2},
    {"tol1e-4", SolverKind::kPcg, 1e-4, 1000, 8e-6, 33.6},
    {"tol1e-5", SolverKind::kPcg, 1e-5, 1000, 8e-7, 43.7},
    {"tol1e-6", SolverKind::kPcg, 1e-6, 1000, 2e-7, 50.9},
    {"tol1e-8", SolverKind::kPcg, 1e-8, 1000, 2e-10, 70.6},
    {"rest5", SolverKind::kPcgCholmod, 0.0, 5, 0.0032, 62.0},
    {"rest10", SolverKind::kPcgCholmod, 0.0, 10, 0.00011, 87.0},
};

// docs/plots/render_phong_accuracy.csv and render_frame_time.csv: bench/render BM_PhongAccuracy
// and BM_FrameTime, the once-subdivided icosahedron (80 triangles) against the unit sphere.
constexpr TessellationCurvePoint kTessellationCurve[] = {
    {1, 0.0269923, 17.7214}, {2, 0.00774037, 44.367}, {3, 0.0118722, 35.9805},
    {4, 0.0139017, 39.0643}, {5, 0.0148377, 62.0075}, {6, 0.0153452, 54.1444},
};

}  // namespace

std::span<const SolverCurvePoint> solver_curve() noexcept { return kSolverCurve; }
std::span<const TessellationCurvePoint> tessellation_curve() noexcept { return kTessellationCurve; }

double quality_accuracy_target(Quality q) noexcept {
  switch (q) {
    case Quality::kFast:
      return 0.05;  // 5 %: past the knee of the CG-cap curve (49 % at cap 20, 2.8 % at cap 50)
    case Quality::kBalanced:
      return 0.01;  // 1 %: the accuracy bar for the 19k box
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
