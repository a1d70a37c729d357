// load_rubric: a rubric's TOML file -> checked Rubric (docs/assessment.md).

#include <algorithm>
#include <cmath>
#include <string>

#include "engine/input_error.h"
#include "engine/scene/rubric.h"
#include "engine/scene/toml_reader.h"

namespace serosa {

namespace {

// Values the session reports under a fixed name, and families with a tool's or a group's name.
constexpr std::array<std::string_view, 28> kFixed = {"time_s",
                                                     "idle_time_s",
                                                     "bimanual_fraction",
                                                     "exchanges",
                                                     "out_of_body_s",
                                                     "path_length_m",
                                                     "force_over_s",
                                                     "peak_stress_pa",
                                                     "cut.deviation_max_m",
                                                     "cut.deviation_mean_m",
                                                     "cut.collateral_m3",
                                                     "out_of_view_s",
                                                     "targets_missed",
                                                     "targets_time_s",
                                                     "bleeding_events",
                                                     "thermal_injuries",
                                                     "procedure.steps_done",
                                                     "procedure.specimen_volume_fraction",
                                                     "transections_above_securing",
                                                     "specimens_dropped",
                                                     "clips_on_artery",
                                                     "clips_off_artery",
                                                     "clip_target_error_m",
                                                     "transfer.handoffs",
                                                     "transfer.drops",
                                                     "transfer.placed",
                                                     "transfer.placement_error_m",
                                                     "tears"};
constexpr std::array<std::string_view, 6> kFamilies = {
    "path_length_m", "force_max_n", "pieces", "out_of_view_s", "step_time_s", "step_path_length_m"};

class RubricReader {
 public:
  explicit RubricReader(std::filesystem::path file) : m_in(std::move(file)) {}

  Rubric read() {
    const toml::table root = m_in.parse("a rubric in TOML");
    Rubric r;
    r.file = m_in.file();
    m_in.check_keys(root, "", {"title", "pass_score", "metric"});
    if (const auto* n = root.get("title")) r.title = m_in.text(*n, "title");
    if (const auto* n = root.get("pass_score")) {
      r.pass_score = m_in.number(*n, "pass_score");
      if (!(r.pass_score >= 0.0 && r.pass_score <= 100.0))
        m_in.fail(*n, "pass_score", "out of range", "a score within [0, 100]");
    }
    const auto* metrics = root.get("metric");
    const auto* arr = metrics != nullptr ? metrics->as_array() : nullptr;
    if (arr == nullptr || arr->empty() || !arr->is_array_of_tables())
      throw InputError(m_in.file().string(), 0, "no [[metric]] tables",
                       "one [[metric]] per value scored");
    for (std::size_t i = 0; i < arr->size(); ++i)
      r.metrics.push_back(metric(*(*arr)[i].as_table(), "metric[" + std::to_string(i) + "]"));
    return r;
  }

 private:
  RubricMetric metric(const toml::table& t, const std::string& p) {
    m_in.check_keys(t, p,
                    {"name", "domain", "unit", "good", "poor", "limit", "weight", "critical"});
    RubricMetric m;
    m.line = static_cast<int>(t.source().begin.line);
    m.name = m_in.text(m_in.required(t, p, "name"), p + ".name");
    std::string family, suffix;
    if (!known_metric(m.name, family, suffix))
      m_in.fail(*t.get("name"), p + ".name", "no metric named '" + m.name + "'",
                "a metric docs/assessment.md lists");
    m.domain = m_in.text(m_in.required(t, p, "domain"), p + ".domain");
    if (std::find(kGoalsDomains.begin(), kGoalsDomains.end(), m.domain) == kGoalsDomains.end())
      m_in.fail(*t.get("domain"), p + ".domain", "unknown domain '" + m.domain + "'",
                "depth_perception, bimanual_dexterity, efficiency, tissue_handling or autonomy");
    if (const auto* n = t.get("unit")) m.unit = m_in.text(*n, p + ".unit");
    m.good = m_in.number(m_in.required(t, p, "good"), p + ".good");
    m.poor = m_in.number(m_in.required(t, p, "poor"), p + ".poor");
    if (m.good == m.poor)
      m_in.fail(*t.get("poor"), p + ".poor", "equal to good", "a value other than good's");
    m.limit = 0.5 * (m.good + m.poor);
    if (const auto* n = t.get("limit")) {
      m.limit = m_in.number(*n, p + ".limit");
      if (m.limit < std::min(m.good, m.poor) || m.limit > std::max(m.good, m.poor))
        m_in.fail(*n, p + ".limit", "outside [good, poor]", "a value between good and poor");
    }
    if (const auto* n = t.get("weight")) {
      m.weight = m_in.number(*n, p + ".weight");
      if (!(m.weight > 0.0)) m_in.fail(*n, p + ".weight", "not positive", "a weight > 0");
    }
    if (const auto* n = t.get("critical")) m.critical = m_in.boolean(*n, p + ".critical");
    return m;
  }

  TomlReader m_in;
};

}  // namespace

bool known_metric(std::string_view name, std::string& family, std::string& suffix) {
  if (std::find(kFixed.begin(), kFixed.end(), name) != kFixed.end()) {
    family = std::string(name);
    suffix.clear();
    return true;
  }
  const std::size_t dot = name.find('.');
  if (dot == std::string_view::npos || dot + 1 >= name.size()) return false;
  const std::string_view head = name.substr(0, dot);
  if (std::find(kFamilies.begin(), kFamilies.end(), head) == kFamilies.end()) return false;
  family = std::string(head);
  suffix = std::string(name.substr(dot + 1));
  return true;
}

Rubric load_rubric(const std::filesystem::path& file) {
  if (!std::filesystem::is_regular_file(file))
    throw InputError(file.string(), 0, "no such rubric file", "a rubric TOML file");
  return RubricReader(file).read();
}

}  // namespace serosa
