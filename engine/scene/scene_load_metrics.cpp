// The scene's [metrics] table (force limit, planned cut, transfer, procedure, rubric) and the
// checks of its rubric against what the scene measures (docs/scene-format.md, docs/assessment.md).
#include "engine/scene/scene_loader.h"

#include <algorithm>
#include <limits>
#include <utility>

namespace serosa::scene_detail {

void Loader::read_metrics(const toml::table& t, MetricsSettings& m) {
  const std::string p = "metrics";
  check_keys(t, p,
             {"planned_cut", "cut_band", "force_limit", "tear_stress", "view_targets", "artery",
              "protected", "clip_target", "transfer", "procedure", "rubric"});
  if (const auto* n = t.get("transfer")) read_transfer(*n, sub(p, "transfer"), m);
  if (const auto* n = t.get("procedure")) read_procedure(*n, sub(p, "procedure"), m);
  if (const auto* n = t.get("artery")) {
    m.artery = string(*n, sub(p, "artery"), "a group name");
    m_group_refs.push_back({line_of(*n), sub(p, "artery"), *m.artery});
  }
  if (const auto* n = t.get("clip_target")) {
    m.clip_target_m = vec3(*n, sub(p, "clip_target"), "[x, y, z] in m (at rest)");
    m_clip_target_line = line_of(*n);
  }
  if (const auto* n = t.get("protected")) {
    const std::string expected = "a list of group names";
    const toml::array& a = array(*n, sub(p, "protected"), expected);
    for (std::size_t i = 0; i < a.size(); ++i) {
      m.protected_groups.push_back(string(a[i], at(sub(p, "protected"), i), expected));
      m_group_refs.push_back(
          {line_of(a[i]), at(sub(p, "protected"), i), m.protected_groups.back()});
    }
  }
  if (const auto* n = t.get("planned_cut")) {
    const std::string expected = "a polyline [[x, y, z], [x, y, z], ...] of >= 2 points in m";
    const auto* a = n->as_array();
    if (a == nullptr || a->size() < 2) fail(*n, sub(p, "planned_cut"), "not a polyline", expected);
    for (std::size_t i = 0; i < a->size(); ++i)
      m.planned_cut_m.push_back(vec3((*a)[i], at(sub(p, "planned_cut"), i), expected));
  }
  if (const auto* n = t.get("view_targets")) {
    const std::string expected = "a list of points [[x, y, z], ...] (at least one) in m";
    const auto* a = n->as_array();
    if (a == nullptr || a->empty()) fail(*n, sub(p, "view_targets"), "not a list", expected);
    for (std::size_t i = 0; i < a->size(); ++i)
      m.view_targets_m.push_back(vec3((*a)[i], at(sub(p, "view_targets"), i), expected));
  }
  if (const auto* n = t.get("cut_band")) {
    m.cut_band_m = ranged(*n, sub(p, "cut_band"), 0.0, true,
                          std::numeric_limits<double>::infinity(), false, "a distance > 0 in m");
  }
  if (const auto* n = t.get("tear_stress"))
    m.tear_stress_pa = ranged(*n, sub(p, "tear_stress"), 0.0, true,
                              std::numeric_limits<double>::infinity(), false, "a stress > 0 in Pa");
  if (const auto* n = t.get("force_limit")) {
    m.force_limit_n = ranged(*n, sub(p, "force_limit"), 0.0, true,
                             std::numeric_limits<double>::infinity(), false, "a force > 0 in N");
  }
  if (const auto* n = t.get("rubric")) {
    const std::string rel = string(*n, sub(p, "rubric"), "a rubric file's path");
    m.rubric = load_rubric(resolve(rel));
    m_rubric_line = line_of(*n);
  }
}

void Loader::read_transfer(const toml::node& n, const std::string& p, MetricsSettings& m) {
  const auto* t = n.as_table();
  if (t == nullptr)
    fail(n, p, "not a table", "{ object = \"group\", target = [x, y, z], radius = r }");
  check_keys(*t, p, {"object", "target", "radius"});
  TransferSettings s;
  const toml::node& object = required(*t, "object", p, "a group name");
  s.object = string(object, sub(p, "object"), "a group name");
  m_group_refs.push_back({line_of(object), sub(p, "object"), s.object});
  s.target_m =
      vec3(required(*t, "target", p, "[x, y, z] in m"), sub(p, "target"), "[x, y, z] in m");
  if (const auto* r = t->get("radius"))
    s.radius_m = ranged(*r, sub(p, "radius"), 0.0, true, std::numeric_limits<double>::infinity(),
                        false, "a radius > 0 in m");
  m.transfer = s;
}

void Loader::read_procedure(const toml::node& n, const std::string& p, MetricsSettings& m) {
  const std::string expected = "{ specimen = GROUP, base = GROUP, mesentery = GROUP }";
  const auto* t = n.as_table();
  if (t == nullptr) fail(n, p, "expected a table, got " + std::string(type_name(n)), expected);
  check_keys(*t, p, {"specimen", "base", "mesentery"});
  ProcedureGroups g;
  for (auto [key, out] : {std::pair<const char*, std::string*>{"specimen", &g.specimen},
                          {"base", &g.base},
                          {"mesentery", &g.mesentery}}) {
    const toml::node& v = required(*t, key, p, "a group name");
    *out = string(v, sub(p, key), "a group name");
    m_group_refs.push_back({line_of(v), sub(p, key), *out});
  }
  m.procedure = g;
  m_procedure_line = line_of(n);
}

// The rubric's metrics name tools and groups of this scene, and some need an effect or a key.
void Loader::check_rubric(const Scene& scene) const {
  if (!scene.metrics.rubric) return;
  const std::string p = "metrics.rubric";
  std::size_t hands = 0;
  for (const Tool& tool : scene.tools) hands += tool.kind != ToolKind::kEndoscope ? 1 : 0;
  for (const RubricMetric& m : scene.metrics.rubric->metrics) {
    std::string family, suffix;
    (void)known_metric(m.name, family, suffix);
    const std::string what = "the rubric's metric '" + m.name + "' (" +
                             scene.metrics.rubric->file.string() + ":" + std::to_string(m.line) +
                             ")";
    const bool tool = std::any_of(scene.tools.begin(), scene.tools.end(),
                                  [&](const Tool& x) { return x.name == suffix; });
    if ((family == "path_length_m" || family == "force_max_n") && !suffix.empty() && !tool)
      fail(m_rubric_line, p, what + " names no tool of this scene", "a [[tool]] name");
    if ((family == "force_max_n" || family == "force_over_s") &&
        !scene.settings.has(Effect::kContact))
      fail(m_rubric_line, p, what + " needs effect \"contact\"", "\"contact\" listed");
    if (family.rfind("cut.", 0) == 0 && scene.metrics.planned_cut_m.empty())
      fail(m_rubric_line, p, what + " needs a planned cut", "metrics.planned_cut");
    if (family == "bimanual_fraction" && hands < 2)
      fail(m_rubric_line, p, what + " needs two hand instruments", "two non-endoscope tools");
    if (family == "pieces" && !has_group(scene, suffix))
      fail(m_rubric_line, p, what + " names no group of this scene", "an organ's group name");
    const bool scope = std::any_of(scene.tools.begin(), scene.tools.end(),
                                   [](const Tool& x) { return x.kind == ToolKind::kEndoscope; });
    if ((family == "out_of_view_s" || family.rfind("targets_", 0) == 0) && !scope)
      fail(m_rubric_line, p, what + " needs an endoscope", "a [[tool]] of kind endoscope");
    if (family == "out_of_view_s" && !suffix.empty() && !tool)
      fail(m_rubric_line, p, what + " names no tool of this scene", "a [[tool]] name");
    if (family.rfind("targets_", 0) == 0 && scene.metrics.view_targets_m.empty())
      fail(m_rubric_line, p, what + " needs targets to look at", "metrics.view_targets");
    if (family == "bleeding_events" && !scene.metrics.artery)
      fail(m_rubric_line, p, what + " needs an artery to watch", "metrics.artery");
    if (family == "thermal_injuries" && scene.metrics.protected_groups.empty())
      fail(m_rubric_line, p, what + " needs protected tissue to watch", "metrics.protected");
    const bool steps = family.rfind("procedure.", 0) == 0 ||
                       family == "transections_above_securing" || family == "specimens_dropped";
    if (steps && !scene.metrics.procedure)
      fail(m_rubric_line, p, what + " needs the procedure's steps followed", "metrics.procedure");
    check_rubric_task(scene, family, suffix, what);
  }
}

// The families the curriculum's tasks add: the procedure's steps, clips.
void Loader::check_rubric_task(const Scene& scene, const std::string& family,
                               const std::string& suffix, const std::string& what) const {
  const std::string p = "metrics.rubric";
  if (family == "step_time_s" || family == "step_path_length_m") {
    if (!scene.metrics.procedure)
      fail(m_rubric_line, p, what + " needs the procedure's steps followed", "metrics.procedure");
    if (std::find(kProcedureSteps.begin(), kProcedureSteps.end(), suffix) == kProcedureSteps.end())
      fail(m_rubric_line, p, what + " names no step of the procedure",
           "expose, divide_mesentery, secure_base, transect or extract");
  }
  const bool clips = family == "clips_on_artery" || family == "clips_off_artery" ||
                     family == "clip_target_error_m";
  if (clips && !scene.settings.has(Effect::kClips))
    fail(m_rubric_line, p, what + " needs effect \"clips\"", "\"clips\" listed");
  if (clips && !scene.metrics.artery)
    fail(m_rubric_line, p, what + " needs an artery to watch", "metrics.artery");
  if (family == "clip_target_error_m" && !scene.metrics.clip_target_m)
    fail(m_rubric_line, p, what + " needs where the clip should go", "metrics.clip_target");
  if (family == "tears" && !scene.metrics.tear_stress_pa)
    fail(m_rubric_line, p, what + " needs the stress at which tissue tears", "metrics.tear_stress");
  if (family.rfind("transfer.", 0) == 0 && !scene.metrics.transfer)
    fail(m_rubric_line, p, what + " needs a transfer to follow", "metrics.transfer");
  if (family.rfind("transfer.", 0) == 0 && !scene.settings.has(Effect::kContact))
    fail(m_rubric_line, p, what + " needs effect \"contact\" (grasps)", "\"contact\" listed");
}

bool Loader::has_group(const Scene& scene, const std::string& name) {
  for (const Organ& o : scene.organs)
    for (const auto& [id, g] : o.groups)
      if (g == name) return true;
  return false;
}

}  // namespace serosa::scene_detail
