#include "app/session_summary.h"

#include <fmt/format.h>

#include <algorithm>
#include <string>

#include "engine/scene/rubric.h"

namespace serosa::app {
namespace {

using Json = nlohmann::json;

std::string words_of(std::string name) {
  std::replace(name.begin(), name.end(), '_', ' ');
  std::replace(name.begin(), name.end(), '.', ' ');
  return name;
}

// "0:08.0 bleeding: ..." when the time says more than the run's end does.
std::string failure_line(const Failure& f, double end_s) {
  if (f.at_s.size() != 1 || f.at_s.front() >= end_s - 1e-9) return f.words;
  return render::clock_text(f.at_s.front()) + "  " + f.words;
}

void add_failures(render::SessionSummary& s, const Json& assessment,
                  const std::vector<Failure>& failed, double end_s) {
  if (!assessment.value("passed", true) &&
      assessment.value("score", 0.0) < assessment.value("pass_score", 0.0))
    s.failed.push_back(fmt::format("score {:.0f}, under the {:.0f} it takes to pass",
                                   assessment.value("score", 0.0),
                                   assessment.value("pass_score", 0.0)));
  for (const Failure& f : failed)
    (f.critical ? s.failed : s.below).push_back(failure_line(f, end_s));
}

void add_steps(render::SessionSummary& s, const Json& metrics) {
  if (!metrics.contains("procedure")) return;
  for (const Json& st : metrics["procedure"].value("steps", Json::array())) {
    render::SummaryStep step;
    step.name = words_of(st.value("name", std::string("?")));
    step.done = st.value("done", false);
    step.duration_s = st.value("duration_s", 0.0);
    if (step.done && st["time_s"].is_number())
      step.start_s = st["time_s"].get<double>() - step.duration_s;
    if (st["tool"].is_string()) step.tool = st["tool"].get<std::string>();
    s.steps.push_back(std::move(step));
  }
}

// One metric's line: "peak stress pa 4e+07 Pa (limit 6e+05)  FAILED".
std::string metric_line(const std::string& name, const Json& m) {
  const std::string unit = m.value("unit", std::string());
  return fmt::format("{}  {:.3g}{}{} (limit {:.3g}){}", words_of(name), m.value("value", 0.0),
                     unit == "1" ? "" : " ", unit == "1" ? std::string() : unit,
                     m.value("threshold", 0.0), m.value("passed", true) ? "" : "  FAILED");
}

void add_groups(render::SessionSummary& s, const Json& assessment) {
  const Json metrics = assessment.value("metrics", Json::object());
  for (const std::string_view d : kGoalsDomains) {
    render::SummaryGroup g;
    g.domain = words_of(std::string(d));
    std::vector<std::string> passed;
    for (const auto& [name, m] : metrics.items()) {
      if (m.value("domain", std::string()) != d || !m["value"].is_number()) continue;
      if (m["value"].get<double>() == 0.0) continue;  // nothing to say
      (m.value("passed", true) ? passed : g.lines).push_back(metric_line(name, m));
    }
    g.lines.insert(g.lines.end(), passed.begin(), passed.end());
    if (!g.lines.empty()) s.groups.push_back(std::move(g));
  }
}

}  // namespace

render::SessionSummary session_summary(const nlohmann::json& report,
                                       const std::vector<Failure>* failed) {
  const Json& assessment = report.at("assessment");
  const Json none = Json::object();
  const Json& metrics = report.contains("metrics") ? report["metrics"] : none;
  render::SessionSummary s;
  s.title = assessment.value("title", std::string());
  s.score = assessment.at("score").get<double>();
  s.pass_score = assessment.at("pass_score").get<double>();
  s.passed = assessment.at("passed").get<bool>();
  for (const std::string_view d : kGoalsDomains) {  // GOALS order, not the JSON's
    const std::string key(d);
    if (assessment["domains"].contains(key))
      s.domains.emplace_back(words_of(key), assessment["domains"][key].get<int>());
  }
  RunEvents at_end;
  at_end.end_s = metrics.value("time_s", 0.0);
  const std::vector<Failure> own =
      failed != nullptr ? std::vector<Failure>{} : failures(report, at_end);
  add_failures(s, assessment, failed != nullptr ? *failed : own, at_end.end_s);
  add_steps(s, metrics);
  add_groups(s, assessment);
  return s;
}

}  // namespace serosa::app
