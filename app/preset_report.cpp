#include "app/preset_report.h"

#include <string>

#include "engine/scene/presets.h"

namespace serosa::app {

nlohmann::json solver_report(const SolverSettings& solver) {
  nlohmann::json j = {{"kind", std::string(solver_kind_name(solver.kind))},
                      {"tolerance", solver.tolerance},
                      {"max_iterations", solver.max_iterations},
                      {"threads", solver.threads}};
  if (solver.kind == SolverKind::kPcgLagged) {
    j["refresh_iterations"] = solver.refresh_iterations;
    j["factor_lag_steps"] = solver.factor_lag_steps;
    j["urgent_lag_steps"] = solver.urgent_lag_steps;
    j["cut_lag_steps"] = solver.cut_lag_steps;
    j["misfit_rad"] = solver.misfit_rad;
    j["patch_rings"] = solver.patch_rings;
    j["after_cut"] = solver.patch_after_cut ? "patch" : "factor";
  }
  return j;
}

std::optional<nlohmann::json> preset_report(const Scene& scene) {
  const auto choice = scene_preset(scene.settings);
  if (!choice) return std::nullopt;
  nlohmann::json j;
  if (scene.settings.quality) j["quality"] = std::string(quality_name(*scene.settings.quality));
  j["target_rel_error"] = choice->target;
  j["target_met"] = choice->target_met;
  const SolverCurvePoint& p = *choice->solver;
  SolverSettings chosen;
  RenderSettings chosen_render;
  apply_preset(*choice, chosen, chosen_render);
  j["solver"] = solver_report(chosen);
  j["solver"]["measured_setting"] = std::string(p.setting);
  j["solver"]["measured_rel_error"] = p.rel_error;
  j["solver"]["measured_ms_per_step"] = p.ms_per_step;
  j["solver"]["measured_on"] = "17.5k-tet SOFA box, docs/BENCHMARKS.md Presets";
  j["solver"]["overridden"] = chosen.kind != scene.solver.kind ||
                              chosen.tolerance != scene.solver.tolerance ||
                              chosen.max_iterations != scene.solver.max_iterations;
  if (choice->tessellation) {
    const TessellationCurvePoint& t = *choice->tessellation;
    j["tessellation"] = {{"level", t.level},
                         {"measured_mean_rel_distance", t.mean_rel_distance},
                         {"measured_frame_ms", t.frame_ms},
                         {"overridden", t.level != scene.render.tessellation}};
  }
  return j;
}

}  // namespace serosa::app
