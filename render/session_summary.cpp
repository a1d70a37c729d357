#include "render/session_summary.h"

#include <algorithm>
#include <cmath>

namespace serosa::render {

std::vector<std::string> summary_text(const SessionSummary& s) {
  std::vector<std::string> out;
  out.push_back(s.title.empty() ? std::string("Session") : s.title);
  out.emplace_back(s.passed ? "PASSED" : "NOT PASSED");
  out.push_back("score " + std::to_string(std::lround(s.score)) + " of 100 (" +
                std::to_string(std::lround(s.pass_score)) + " to pass)");
  for (const auto& [name, rating] : s.domains)
    out.push_back(name + "  " + std::to_string(rating) + " / 5");
  if (!s.failed.empty()) {
    out.emplace_back("Why:");
    for (const std::string& f : s.failed) out.push_back("  " + f);
  }
  std::vector<std::string> more;
  for (const std::string& b : s.below)
    if (std::find(s.failed.begin(), s.failed.end(), b) == s.failed.end()) more.push_back(b);
  if (!more.empty()) {
    out.emplace_back("To work on:");
    for (const std::string& b : more) out.push_back("  " + b);
  }
  out.emplace_back("Esc, Space or close the window to leave");
  return out;
}

}  // namespace serosa::render
