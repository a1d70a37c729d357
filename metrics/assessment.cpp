#include "metrics/assessment.h"

#include <algorithm>
#include <cmath>
#include <sstream>
#include <stdexcept>

namespace serosa::metrics {

namespace {

// 1 at or beyond good, 0 at or beyond poor, linear between (either direction).
double metric_score(const RubricMetric& m, double v) {
  return std::clamp((m.poor - v) / (m.poor - m.good), 0.0, 1.0);
}

bool metric_passed(const RubricMetric& m, double v) {
  return m.good < m.poor ? v <= m.limit : v >= m.limit;
}

std::string why_failed(const RubricMetric& m, double v) {
  std::ostringstream s;
  const bool unitless = m.unit.empty() || m.unit == "1";  // counts and fractions
  s << m.name << " = " << v << (unitless ? "" : " ") << (unitless ? "" : m.unit)
    << (m.good < m.poor ? ", above the limit of " : ", below the limit of ") << m.limit
    << (m.critical ? " (critical)" : "");
  return s.str();
}

}  // namespace

Assessment assess(const Rubric& rubric, const std::map<std::string, double>& values) {
  Assessment a;
  double sum = 0.0, weights = 0.0;
  std::map<std::string, std::pair<double, double>> domain;  // weighted score, weight
  for (const RubricMetric& m : rubric.metrics) {
    const auto it = values.find(m.name);
    if (it == values.end())
      throw std::invalid_argument("assessment: the session did not measure '" + m.name + "'");
    MetricScore s{&m, it->second, metric_score(m, it->second), metric_passed(m, it->second)};
    sum += m.weight * s.score;
    weights += m.weight;
    auto& [ds, dw] = domain[m.domain];
    ds += m.weight * s.score;
    dw += m.weight;
    if (!s.passed && m.critical) a.failed.push_back(why_failed(m, s.value));
    a.metrics.push_back(s);
  }
  a.score = weights > 0.0 ? 100.0 * sum / weights : 0.0;
  // GOALS rates each domain on whole points from 1 to 5.
  for (const auto& [name, sw] : domain)
    a.domains[name] = static_cast<int>(std::lround(1.0 + 4.0 * sw.first / sw.second));
  if (a.score < rubric.pass_score) {
    std::vector<std::string> failed{"score " + std::to_string(std::lround(a.score)) +
                                    " under the pass score of " +
                                    std::to_string(std::lround(rubric.pass_score))};
    failed.insert(failed.end(), a.failed.begin(), a.failed.end());
    a.failed = std::move(failed);
  }
  a.passed = a.failed.empty();
  return a;
}

nlohmann::json assessment_json(const Assessment& a, const Rubric& rubric) {
  nlohmann::json j;
  j["rubric"] = rubric.file.string();
  j["title"] = rubric.title;
  j["score"] = a.score;
  j["pass_score"] = rubric.pass_score;
  j["passed"] = a.passed;
  j["domains"] = nlohmann::json::object();
  for (const auto& [name, rating] : a.domains) j["domains"][name] = rating;
  j["metrics"] = nlohmann::json::object();
  for (const MetricScore& s : a.metrics)
    j["metrics"][s.rule->name] = {
        {"value", s.value},     {"threshold", s.rule->limit}, {"good", s.rule->good},
        {"poor", s.rule->poor}, {"unit", s.rule->unit},       {"domain", s.rule->domain},
        {"score", s.score},     {"passed", s.passed},         {"critical", s.rule->critical}};
  j["failed"] = a.failed;
  // Failing a non-critical metric does not fail the session, but the trainee should see it.
  nlohmann::json below = nlohmann::json::array();
  for (const MetricScore& s : a.metrics)
    if (!s.passed) below.push_back(why_failed(*s.rule, s.value));
  j["below_threshold"] = std::move(below);
  return j;
}

}  // namespace serosa::metrics
