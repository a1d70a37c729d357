#include "app/session_summary.h"

#include <algorithm>
#include <string>

#include "engine/rubric.h"

namespace serosa::app {

render::SessionSummary session_summary(const nlohmann::json& assessment) {
  render::SessionSummary s;
  s.title = assessment.value("title", std::string());
  s.score = assessment.at("score").get<double>();
  s.pass_score = assessment.at("pass_score").get<double>();
  s.passed = assessment.at("passed").get<bool>();
  for (const std::string_view d : kGoalsDomains) {  // GOALS order, not the JSON's
    const std::string key(d);
    if (!assessment["domains"].contains(key)) continue;
    std::string words = key;
    std::replace(words.begin(), words.end(), '_', ' ');
    s.domains.emplace_back(std::move(words), assessment["domains"][key].get<int>());
  }
  s.failed = assessment.value("failed", std::vector<std::string>{});
  s.below = assessment.value("below_threshold", std::vector<std::string>{});
  return s;
}

}  // namespace serosa::app
