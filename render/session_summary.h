// SessionSummary: what the trainee sees when a session ends (its assessment: score, pass or fail,
// the five GOALS domains, what failed and why), as plain text and numbers; the app fills it from
// the report's assessment (app/session_summary.h) and the overlay draws it (Overlay::draw_summary).
#pragma once

#include <string>
#include <utility>
#include <vector>

namespace serosa::render {

struct SessionSummary {
  std::string title;        ///< what was scored ("Appendix transection")
  double score = 0.0;       ///< 0-100
  double pass_score = 0.0;  ///< 0-100
  bool passed = false;
  std::vector<std::pair<std::string, int>> domains;  ///< GOALS domain (words) -> 1-5
  std::vector<std::string> failed;                   ///< why it did not pass, one line each
  std::vector<std::string> below;                    ///< metrics on the wrong side of their limit
};

/// The banner's colours (RGB bytes): what tests look for in the picture.
inline constexpr unsigned char kPassedRgb[3] = {40, 150, 60};
inline constexpr unsigned char kFailedRgb[3] = {190, 45, 45};

/// The summary, line by line as drawn: the title; "PASSED" or "NOT PASSED"; "score 96 of 100
/// (80 to pass)"; one line per domain, "depth perception  4 / 5"; "Why:" and the failed lines;
/// "To work on:" and the metrics below their limits that are not among them; the way out.
[[nodiscard]] std::vector<std::string> summary_text(const SessionSummary& s);

}  // namespace serosa::render
