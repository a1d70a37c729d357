#include "render/session_summary.h"

#include <algorithm>
#include <cmath>
#include <cstdio>

namespace serosa::render {

std::string clock_text(double seconds) {
  seconds = std::max(seconds, 0.0);
  const int minutes = static_cast<int>(seconds / 60.0);
  char out[32];
  std::snprintf(out, sizeof out, "%d:%04.1f", minutes, seconds - 60.0 * minutes);
  return out;
}

std::vector<std::string> summary_text(const SessionSummary& s, bool with_way_out) {
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
  if (!s.steps.empty()) out.emplace_back("Steps:");
  for (const SummaryStep& st : s.steps) {
    char line[160];
    if (st.done)
      std::snprintf(line, sizeof line, "  %s  %s + %.1f s  %s", st.name.c_str(),
                    clock_text(st.start_s).c_str(), st.duration_s, st.tool.c_str());
    else
      std::snprintf(line, sizeof line, "  %s  not done", st.name.c_str());
    out.emplace_back(line);
  }
  if (with_way_out) out.emplace_back("Esc, Space or close the window to leave");
  return out;
}

}  // namespace serosa::render
