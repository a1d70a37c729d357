// What a run failed on, in an instructor's words and at the times it happened: one entry per
// criterion of the rubric the assessment failed (docs/assessment.md), each with the moments that
// show it (the bleeding's cut, the torn tissue, the clip that missed, the end of the run for a
// step never done). The replay marks them on its timeline; the debrief panel and the trainee's
// end-of-session summary list the words.
#pragma once

#include <map>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

namespace serosa::app {

/// When things happened that the report keeps only as totals (watched step by step by the
/// replay's timeline, replay/replay_timeline.h). Times in s of simulated time; < 0: never.
struct RunEvents {
  std::map<std::string, double> force_max_at_s;  ///< tool name -> when its largest force was
  double peak_stress_at_s = -1.0;                ///< when the largest stress was reached
  double force_over_at_s = -1.0;                 ///< when a tool first went over the force limit
  double collateral_at_s = -1.0;         ///< the step that cut the most tissue off the planned line
  double first_cut_at_s = -1.0;          ///< the first step that cut tissue
  std::vector<double> clip_closed_at_s;  ///< each time a clip applier's jaws closed
  double end_s = 0.0;                    ///< the run's length
};

/// One failed criterion.
struct Failure {
  std::string criterion;     ///< the rubric's metric name ("bleeding_events", "tears")
  std::string words;         ///< what went wrong, plainly ("bleeding: the artery was cut ...")
  std::vector<double> at_s;  ///< when, s (at least one: the run's end when nothing earlier)
  bool critical = false;     ///< a critical criterion (fails the run whatever the score)
};

/// The criteria `report["assessment"]` fails on (its metrics with passed = false), in words, with
/// their times from the report's own lists (errors, tear times, the procedure's steps) and from
/// `events`. Empty without an assessment or when everything passed.
[[nodiscard]] std::vector<Failure> failures(const nlohmann::json& report, const RunEvents& events);

}  // namespace serosa::app
