// Assessment: a session's metrics scored against a rubric (engine/scene/rubric.h,
// docs/assessment.md).
#pragma once

#include <map>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "engine/scene/rubric.h"

namespace serosa::metrics {

struct MetricScore {
  const RubricMetric* rule = nullptr;  ///< the rubric's line for it
  double value = 0.0;                  ///< as the session measured it, in rule->unit
  double score = 0.0;                  ///< 0 (at or beyond poor) .. 1 (at or beyond good)
  bool passed = false;                 ///< on the good side of rule->limit
};

struct Assessment {
  double score = 0.0;   ///< 0-100: the weighted mean of the metrics' scores
  bool passed = false;  ///< score >= the rubric's pass_score and every critical metric passed
  std::map<std::string, int> domains;  ///< GOALS domain -> 1-5
  std::vector<MetricScore> metrics;    ///< in the rubric's order
  std::vector<std::string> failed;     ///< why it did not pass, one line each (empty: passed)
};

/// Scores `values` (metric name -> value, every name the rubric lists; throws
/// std::invalid_argument naming one that is missing) against `rubric`.
[[nodiscard]] Assessment assess(const Rubric& rubric, const std::map<std::string, double>& values);

/// The report's "assessment": score, passed, domains, metrics (value, threshold, unit, score,
/// passed for each), failed, rubric.
[[nodiscard]] nlohmann::json assessment_json(const Assessment& a, const Rubric& rubric);

}  // namespace serosa::metrics
