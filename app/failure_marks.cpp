#include "app/failure_marks.h"

#include <fmt/format.h>

#include <algorithm>
#include <string_view>

namespace serosa::app {
namespace {

using Json = nlohmann::json;

// One failed metric of the assessment, and what the whole report says.
struct Criterion {
  const std::string& name;
  const Json& m;  // the assessment's entry: value, threshold, unit, critical ...
  const Json& metrics;
  const RunEvents& ev;

  [[nodiscard]] double value() const { return m.value("value", 0.0); }
  [[nodiscard]] double limit() const { return m.value("threshold", 0.0); }
};

bool starts_with(std::string_view s, std::string_view p) { return s.substr(0, p.size()) == p; }

// The times of the report's procedure errors of one kind ("bleeding", ...).
std::vector<double> error_times(const Json& metrics, std::string_view kind) {
  std::vector<double> t;
  if (!metrics.contains("errors")) return t;
  for (const Json& e : metrics["errors"])
    if (e.value("kind", std::string()) == kind) t.push_back(e.value("time_s", 0.0));
  return t;
}

std::vector<double> json_times(const Json& list) {
  std::vector<double> t;
  if (list.is_array())
    for (const Json& x : list) t.push_back(x.get<double>());
  return t;
}

std::vector<double> at_or_end(double t, const RunEvents& ev) { return {t >= 0.0 ? t : ev.end_s}; }

// The tool's name after "metric." ("force_max_n.grasper" -> "grasper"); empty for none.
std::string suffix(const std::string& name) {
  const std::size_t dot = name.find('.');
  return dot == std::string::npos ? std::string() : name.substr(dot + 1);
}

// The procedure's step `name`'s end, s (< 0: not found or not done).
double step_end_s(const Json& metrics, const std::string& name) {
  if (!metrics.contains("procedure")) return -1.0;
  for (const Json& s : metrics["procedure"].value("steps", Json::array()))
    if (s.value("name", std::string()) == name && s["time_s"].is_number())
      return s["time_s"].get<double>();
  return -1.0;
}

// A step never done: one failure each, at the run's end.
void steps_not_done(const Criterion& c, std::vector<Failure>& out) {
  bool any = false;
  if (c.metrics.contains("procedure")) {
    for (const Json& s : c.metrics["procedure"].value("steps", Json::array())) {
      if (s.value("done", false)) continue;
      std::string step = s.value("name", std::string("?"));
      std::replace(step.begin(), step.end(), '_', ' ');
      out.push_back({c.name, "step not done: " + step, {c.ev.end_s}, false});
      any = true;
    }
  }
  if (!any)
    out.push_back(
        {c.name,
         fmt::format("{:.0f} of the procedure's steps done ({:.0f} needed)", c.value(), c.limit()),
         {c.ev.end_s},
         false});
}

// The criteria the report's error list times (metrics/procedure_errors.h), and their words.
struct ErrorCriterion {
  std::string_view criterion, kind, words;
};
constexpr ErrorCriterion kErrorCriteria[] = {
    {"bleeding_events", "bleeding", "bleeding: the artery was cut before it was secured"},
    {"thermal_injuries", "thermal_injury",
     "thermal injury: the live hook burnt tissue it must spare"},
    {"transections_above_securing", "transection_above_securing",
     "transected above the loop or clip that secures the base"},
    {"specimens_dropped", "specimen_dropped", "the specimen was dropped"},
};

// The words and times of the criteria that have an event of their own.
bool event_failure(const Criterion& c, Failure& f) {
  const std::string& n = c.name;
  for (const ErrorCriterion& e : kErrorCriteria) {
    if (n != e.criterion) continue;
    f.words = e.words;
    f.at_s = error_times(c.metrics, e.kind);
    return true;
  }
  if (n != "tears") return false;
  f.words = fmt::format("tissue torn {:.0f} time{} (pulled past its strength)", c.value(),
                        c.value() == 1.0 ? "" : "s");
  f.at_s = json_times(c.metrics.value("tear_times_s", Json::array()));
  return true;
}

// The words and times of the criteria measured as amounts.
bool amount_failure(const Criterion& c, Failure& f) {
  const std::string& n = c.name;
  const double v = c.value();
  const double lim = c.limit();
  if (n == "peak_stress_pa") {
    f.words =
        fmt::format("tissue overstressed: {:.2g} MPa (limit {:.2g} MPa)", v * 1e-6, lim * 1e-6);
    f.at_s = at_or_end(c.ev.peak_stress_at_s, c.ev);
  } else if (starts_with(n, "force_max_n.")) {
    const std::string tool = suffix(n);
    f.words = fmt::format("{} pulled too hard: {:.1f} N (limit {:.1f} N)", tool, v, lim);
    const auto it = c.ev.force_max_at_s.find(tool);
    f.at_s = at_or_end(it == c.ev.force_max_at_s.end() ? -1.0 : it->second, c.ev);
  } else if (n == "force_over_s") {
    f.words = fmt::format("instruments over the force limit for {:.1f} s (limit {:.1f} s)", v, lim);
    f.at_s = at_or_end(c.ev.force_over_at_s, c.ev);
  } else if (n == "cut.collateral_m3") {
    f.words =
        fmt::format("cut {:.0f} mm3 off the planned line (limit {:.0f} mm3)", v * 1e9, lim * 1e9);
    f.at_s = at_or_end(c.ev.collateral_at_s, c.ev);
  } else if (starts_with(n, "cut.deviation")) {
    f.words = fmt::format("the cut strayed {:.1f} mm from the planned line{} (limit {:.1f} mm)",
                          v * 1e3, n == "cut.deviation_mean_m" ? " on average" : "", lim * 1e3);
    f.at_s =
        at_or_end(c.ev.collateral_at_s >= 0.0 ? c.ev.collateral_at_s : c.ev.first_cut_at_s, c.ev);
  } else if (n == "procedure.specimen_volume_fraction") {
    f.words = fmt::format("specimen not extracted: {:.0f} % of the appendix out ({:.0f} % needed)",
                          100.0 * v, 100.0 * lim);
    f.at_s = {c.ev.end_s};
  } else {
    return false;
  }
  return true;
}

// The clip applier's criteria: at each closing of its jaws (the run's end when it never closed).
bool clip_failure(const Criterion& c, Failure& f) {
  const std::string& n = c.name;
  if (n == "clips_on_artery")
    f.words = "clip missed: no clip closed on the artery";
  else if (n == "clips_off_artery")
    f.words =
        fmt::format("{:.0f} clip{} closed off the artery", c.value(), c.value() == 1.0 ? "" : "s");
  else if (n == "clip_target_error_m")
    f.words = fmt::format("clip {:.1f} mm from the marked point (limit {:.1f} mm)", c.value() * 1e3,
                          c.limit() * 1e3);
  else
    return false;
  f.at_s = c.ev.clip_closed_at_s;
  if (f.at_s.empty()) f.at_s = {c.ev.end_s};
  return true;
}

// Criteria judged over the whole run: marked at its end (a step's time at that step's end).
void run_failure(const Criterion& c, Failure& f) {
  const std::string& n = c.name;
  const double v = c.value();
  const double lim = c.limit();
  const std::string tool = suffix(n);
  f.at_s = {c.ev.end_s};
  if (n == "time_s") {
    f.words = fmt::format("took {:.1f} s (limit {:.0f} s)", v, lim);
  } else if (starts_with(n, "step_time_s.")) {
    std::string step = tool;
    std::replace(step.begin(), step.end(), '_', ' ');
    f.words = fmt::format("step {} took {:.1f} s (limit {:.0f} s)", step, v, lim);
    f.at_s = at_or_end(step_end_s(c.metrics, tool), c.ev);
  } else if (n == "idle_time_s") {
    f.words = fmt::format("idle for {:.1f} s (limit {:.0f} s)", v, lim);
  } else if (starts_with(n, "path_length_m")) {
    f.words = fmt::format("{} travelled {:.2f} m (limit {:.2f} m)",
                          tool.empty() ? std::string("the instruments") : tool, v, lim);
  } else if (n == "bimanual_fraction") {
    f.words = fmt::format("both hands worked together {:.0f} % of the time ({:.0f} % needed)",
                          100.0 * v, 100.0 * lim);
  } else if (starts_with(n, "out_of_view_s")) {
    f.words = fmt::format("{} out of the endoscope's view for {:.1f} s (limit {:.1f} s)",
                          tool.empty() ? std::string("instruments") : tool, v, lim);
  } else if (n == "out_of_body_s") {
    f.words = fmt::format("instruments outside the body for {:.1f} s (limit {:.1f} s)", v, lim);
  } else {
    std::string words = n;
    std::replace(words.begin(), words.end(), '_', ' ');
    std::replace(words.begin(), words.end(), '.', ' ');
    const std::string unit = c.m.value("unit", std::string());
    f.words = fmt::format("{}: {:.3g}{}{} (limit {:.3g})", words, v, unit == "1" ? "" : " ",
                          unit == "1" ? std::string() : unit, lim);
  }
}

}  // namespace

std::vector<Failure> failures(const nlohmann::json& report, const RunEvents& events) {
  std::vector<Failure> out;
  if (!report.contains("assessment") || !report["assessment"].is_object()) return out;
  const Json& assessment = report["assessment"];
  const Json none = Json::object();
  const Json& metrics = report.contains("metrics") ? report["metrics"] : none;
  const Json criteria = assessment.value("metrics", Json::object());  // items() needs it alive
  for (const auto& [name, m] : criteria.items()) {
    if (m.value("passed", true)) continue;
    const Criterion c{name, m, metrics, events};
    if (name == "procedure.steps_done") {
      steps_not_done(c, out);
      for (Failure& f : out)
        if (f.criterion == name) f.critical = m.value("critical", false);
      continue;
    }
    Failure f{name, {}, {}, m.value("critical", false)};
    if (!event_failure(c, f) && !amount_failure(c, f) && !clip_failure(c, f)) run_failure(c, f);
    if (f.at_s.empty()) f.at_s = {events.end_s};
    out.push_back(std::move(f));
  }
  // Critical first, then in the order they happened.
  std::stable_sort(out.begin(), out.end(), [](const Failure& a, const Failure& b) {
    if (a.critical != b.critical) return a.critical;
    return a.at_s.front() < b.at_s.front();
  });
  return out;
}

}  // namespace serosa::app
