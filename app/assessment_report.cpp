#include "app/assessment_report.h"

#include <algorithm>

#include "cutting/validate.h"
#include "metrics/assessment.h"

namespace serosa::app {

namespace {

// The values the curriculum's tasks add: what each of the procedure's steps cost, the clips, the
// transfer.
void task_values(const Scene& scene, const metrics::MetricsStage& metrics,
                 std::map<std::string, double>& v) {
  const metrics::StepSplits& splits = metrics.step_splits();
  if (splits.active())
    for (std::size_t i = 0; i < kProcedureSteps.size(); ++i) {
      const std::string step(kProcedureSteps[i]);
      const bool done = metrics.procedure_steps().steps()[i].done;
      // A step not done took the whole run, and all the path since the last one done.
      const metrics::StepSplit& s = done ? splits.split(i) : splits.open();
      v["step_time_s." + step] = done ? s.duration_s : metrics.time_s();
      v["step_path_length_m." + step] = splits.hand_path_m(s);
    }
  const metrics::ClipPlacement& clips = metrics.clip_placement();
  if (clips.active()) {
    v["clips_on_artery"] = clips.on_artery();
    v["clips_off_artery"] = clips.off_artery();
    if (scene.metrics.clip_target_m) v["clip_target_error_m"] = clips.target_error_m();
  }
  const metrics::TransferWatch& transfer = metrics.transfer();
  if (transfer.active()) {
    v["transfer.handoffs"] = transfer.handoffs();
    v["transfer.drops"] = transfer.drops();
    v["transfer.placed"] = transfer.placed() ? 1.0 : 0.0;
    v["transfer.placement_error_m"] = transfer.error_m();
  }
}

}  // namespace

std::map<std::string, double> session_values(const Scene& scene,
                                             const metrics::MetricsStage& metrics,
                                             const TetMesh& mesh,
                                             const std::map<int, std::string>& groups) {
  std::map<std::string, double> v;
  v["time_s"] = metrics.time_s();
  v["idle_time_s"] = metrics.idle_time_s();
  v["bimanual_fraction"] = metrics.bimanual_fraction();
  if (metrics.exchanges().hands_seen()) {
    v["exchanges"] = static_cast<double>(metrics.exchanges().exchanges().size());
    v["out_of_body_s"] = metrics.exchanges().out_of_body_s();
  }
  v["force_over_s"] = metrics.force_over_s();
  v["peak_stress_pa"] = metrics.peak_stress_pa();
  if (scene.metrics.tear_stress_pa) v["tears"] = static_cast<double>(metrics.tears());
  double hands = 0.0, unseen = 0.0;
  const bool scope = std::any_of(scene.tools.begin(), scene.tools.end(),
                                 [](const Tool& t) { return t.kind == ToolKind::kEndoscope; });
  for (std::size_t i = 0; i < scene.tools.size(); ++i) {
    const std::string& name = scene.tools[i].name;
    v["path_length_m." + name] = metrics.path_length_m(i);
    v["force_max_n." + name] = metrics.force_max_n(i);
    if (scene.tools[i].kind == ToolKind::kEndoscope) continue;
    hands += metrics.path_length_m(i);
    unseen += metrics.out_of_view_s(i);
    if (scope) v["out_of_view_s." + name] = metrics.out_of_view_s(i);
  }
  v["path_length_m"] = hands;
  if (scope) v["out_of_view_s"] = unseen;
  if (!scene.metrics.view_targets_m.empty()) {
    v["targets_missed"] = static_cast<double>(metrics.targets_missed());
    v["targets_time_s"] = metrics.targets_time_s();
  }
  if (!scene.metrics.planned_cut_m.empty()) {
    v["cut.deviation_max_m"] = metrics.deviation_max_m();
    v["cut.deviation_mean_m"] = metrics.deviation_mean_m();
    v["cut.collateral_m3"] = metrics.collateral_m3();
  }
  const metrics::ProcedureErrors& errors = metrics.procedure_errors();
  if (scene.metrics.artery)
    v["bleeding_events"] =
        static_cast<double>(errors.count(metrics::ProcedureError::Kind::kBleeding));
  if (!scene.metrics.protected_groups.empty())
    v["thermal_injuries"] =
        static_cast<double>(errors.count(metrics::ProcedureError::Kind::kThermalInjury));
  if (scene.metrics.procedure) {
    const metrics::ProcedureSteps& steps = metrics.procedure_steps();
    v["procedure.steps_done"] = static_cast<double>(std::count_if(
        steps.steps().begin(), steps.steps().end(), [](const auto& s) { return s.done; }));
    v["procedure.specimen_volume_fraction"] = steps.specimen_fraction();
    v["transections_above_securing"] =
        static_cast<double>(errors.count(metrics::ProcedureError::Kind::kTransectionAboveSecuring));
    v["specimens_dropped"] =
        static_cast<double>(errors.count(metrics::ProcedureError::Kind::kSpecimenDropped));
  }
  task_values(scene, metrics, v);
  for (const auto& [id, name] : groups)
    v["pieces." + name] = cutting::count_components(mesh, static_cast<std::uint16_t>(id));
  return v;
}

nlohmann::json assessment_report(const Scene& scene, const metrics::MetricsStage* metrics,
                                 const TetMesh& mesh, const std::map<int, std::string>& groups) {
  if (!scene.metrics.rubric || metrics == nullptr) return nullptr;
  const metrics::Assessment a =
      metrics::assess(*scene.metrics.rubric, session_values(scene, *metrics, mesh, groups));
  return metrics::assessment_json(a, *scene.metrics.rubric);
}

void add_metrics_blocks(nlohmann::json& report, const Scene& scene,
                        const metrics::MetricsStage* metrics, const TetMesh& mesh,
                        const std::map<int, std::string>& groups) {
  if (metrics == nullptr) return;
  report["metrics"] = metrics->report();
  if (report["metrics"].contains("procedure")) report["procedure"] = report["metrics"]["procedure"];
  if (auto a = assessment_report(scene, metrics, mesh, groups); !a.is_null())
    report["assessment"] = std::move(a);
}

}  // namespace serosa::app
