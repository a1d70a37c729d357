// Presets: a scene's `quality` ("fast" | "balanced" | "accurate") or `accuracy_target`
// picks the solver settings and the Phong tessellation level from the accuracy-versus-time curves
// `serosa bench` measured (docs/BENCHMARKS.md "Presets"): the cheapest measured setting whose
// error is within the target. The curves are compiled in (engine/scene/presets.cpp); a test checks
// them against the CSV files of the run they were copied from (docs/plots/), so they cannot drift
// apart silently.
#pragma once

#include <span>
#include <string_view>

#include "engine/scene/scene.h"

namespace serosa {

/// One measured point of the solver's accuracy-versus-time curve on the reference scene (the
/// SOFA-matching box of docs/BENCHMARKS.md "FEM": displacement after 1 s of sagging under
/// gravity, relative to the converged CHOLMOD run).
struct SolverCurvePoint {
  std::string_view setting;  ///< the bench row's label ("cg cap=50")
  SolverKind kind;
  double tolerance;    ///< relative residual the run used (0: ran to the iteration cap)
  int max_iterations;  ///< CG iteration cap the run used
  double rel_error;    ///< max displacement error / max displacement (dimensionless)
  double ms_per_step;  ///< ms per step on the reference box, 2-core machine
};

/// One measured point of the tessellation curve: a coarse surface drawn with Phong tessellation
/// at `level`, against the true surface it approximates.
struct TessellationCurvePoint {
  int level;                 ///< Phong tessellation level (1 = flat)
  double mean_rel_distance;  ///< mean distance to the true surface / its radius (dimensionless)
  double frame_ms;           ///< ms per frame (llvmpipe), the same run
};

/// The measured curves, in the order of the bench run.
[[nodiscard]] std::span<const SolverCurvePoint> solver_curve() noexcept;
[[nodiscard]] std::span<const TessellationCurvePoint> tessellation_curve() noexcept;

/// The relative displacement error each quality preset asks of the solver.
[[nodiscard]] double quality_accuracy_target(Quality q) noexcept;
/// The tessellation target of each quality preset: mean relative distance to the true surface.
[[nodiscard]] double quality_surface_target(Quality q) noexcept;

/// What a preset chose.
struct PresetChoice {
  double target = 0.0;                       ///< relative displacement error asked for
  const SolverCurvePoint* solver = nullptr;  ///< cheapest point within target (never null)
  bool target_met = false;  ///< false: no measured point reaches the target; `solver` is the best
  const TessellationCurvePoint* tessellation = nullptr;  ///< null when no quality was given
};

/// The cheapest solver point with rel_error <= target (the most accurate point when none is),
/// and, when `quality` is given, the cheapest tessellation level within its surface target.
[[nodiscard]] PresetChoice choose_preset(double target, std::optional<Quality> quality);

/// The scene's choice: from settings.accuracy_target (set by the loader from `accuracy_target` or
/// from the quality preset), or nullopt when the scene names neither.
[[nodiscard]] std::optional<PresetChoice> scene_preset(const SceneSettings& settings);

/// Writes the choice into the settings (explicit [solver]/[render] keys are read afterwards by the
/// loader and win). A point measured with tolerance 0 (run to its cap) gets tolerance 1e-10 so a
/// scene at rest stops early; under load the cap binds exactly as measured.
void apply_preset(const PresetChoice& choice, SolverSettings& solver, RenderSettings& render);

}  // namespace serosa
