// A branch's own assessment: once the instructor (or trainee) takes over from a replay, the run
// is no longer the recording's, so its errors and its score are its own. While it runs, its
// timeline keeps the original's marks from before the branch and adds the errors the branch makes
// that no later step can undo (a bleeding, a burn, a tear, a dropped specimen, a transection
// above the securing); when it ends, it is scored like any run.
#pragma once

#include <chrono>
#include <filesystem>
#include <optional>
#include <vector>

#include <nlohmann/json.hpp>

#include "app/failure_marks.h"
#include "render/render_frame.h"

namespace serosa::replay {

class ReplayController;

/// The run's "metrics", "procedure" and "assessment" blocks as they stand now (null without a
/// metrics stage).
[[nodiscard]] nlohmann::json report_so_far(const ReplayController& replay);

/// The branch's timeline: `original`'s marks before `branch_s`, then those of `report`'s failed
/// criteria that are events (see above) after it, in time order.
[[nodiscard]] std::vector<render::TimelineMark> branch_marks(
    const std::vector<render::TimelineMark>& original, double branch_s,
    const nlohmann::json& report);

/// What the replay window shows of a branch while it runs: its marks and its debrief so far,
/// refreshed once a second of wall time (scoring the mesh every frame would cost the replay).
class BranchDebrief {
 public:
  /// Refreshes from `replay` (branched) when a second has passed since the last time, or `now`.
  void update(const ReplayController& replay, const std::vector<render::TimelineMark>& original,
              bool now);
  [[nodiscard]] const std::vector<render::TimelineMark>& marks() const { return m_marks; }
  [[nodiscard]] const std::optional<render::SessionSummary>& summary() const { return m_summary; }

 private:
  std::optional<std::chrono::steady_clock::time_point> m_last;
  std::vector<render::TimelineMark> m_marks;
  std::optional<render::SessionSummary> m_summary;
};

/// Ends the branch's recording and writes its report beside it (`recording` with .json: the
/// branch's step, its "metrics", "procedure" and "assessment"); returns that report.
nlohmann::json finish_branch(ReplayController& replay, const std::filesystem::path& recording);

}  // namespace serosa::replay
