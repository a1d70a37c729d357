// SessionSummary: a run's debrief (its assessment: score, pass or fail, the five GOALS domains,
// what failed in words, the procedure's steps, the rubric's metrics by domain), as plain text and
// numbers. The app fills it from the report (app/session_summary.h); the overlay draws it the same
// way at the end of a trainee's session (Overlay::draw_summary) and beside the instructor's replay
// (OverlayData::debrief).
#pragma once

#include <string>
#include <utility>
#include <vector>

namespace serosa::render {

/// One step of the procedure (docs/procedure.md), as the timeline draws it.
struct SummaryStep {
  std::string name;         ///< in words: "divide mesentery"
  double start_s = 0.0;     ///< when it began, s
  double duration_s = 0.0;  ///< s; 0 when not done
  std::string tool;         ///< the instrument that did it; empty when not done
  bool done = false;
};

/// The rubric's metrics of one GOALS domain, a line each ("peak stress 40 MPa (limit 0.6) FAILED");
/// metrics that read zero are left out.
struct SummaryGroup {
  std::string domain;              ///< in words: "tissue handling"
  std::vector<std::string> lines;  ///< failed ones first
};

struct SessionSummary {
  std::string title;        ///< what was scored ("Appendix transection")
  double score = 0.0;       ///< 0-100
  double pass_score = 0.0;  ///< 0-100
  bool passed = false;
  std::vector<std::pair<std::string, int>> domains;  ///< GOALS domain (words) -> 1-5
  std::vector<std::string> failed;   ///< why it did not pass, in words, one line each
  std::vector<std::string> below;    ///< other criteria on the wrong side of their limit, in words
  std::vector<SummaryStep> steps;    ///< the procedure's steps; empty: the scene has none
  std::vector<SummaryGroup> groups;  ///< the rubric's metrics by domain, GOALS order
};

/// The banner's colours (RGB bytes): what tests look for in the picture.
inline constexpr unsigned char kPassedRgb[3] = {40, 150, 60};
inline constexpr unsigned char kFailedRgb[3] = {190, 45, 45};

/// The summary, line by line as drawn: the title; "PASSED" or "NOT PASSED"; "score 96 of 100
/// (80 to pass)"; one line per domain, "depth perception  4 / 5"; "Why:" and the failed lines;
/// "To work on:" and the metrics below their limits that are not among them; "Steps:" and one
/// line per step ("  divide mesentery  0:02.8 + 5.2 s  hook", "  transect  not done"); the way
/// out (`with_way_out`: the trainee's screen, not the replay's panel).
[[nodiscard]] std::vector<std::string> summary_text(const SessionSummary& s,
                                                    bool with_way_out = true);

/// "m:ss.s".
[[nodiscard]] std::string clock_text(double seconds);

}  // namespace serosa::render
