// The replay's timeline (instructors): the tools' force on the tissue over the whole recording,
// and the run's assessment with each criterion it failed marked where it happened (app/
// failure_marks.h), so that N and P jump from one to the next.
//
// Computed by replaying the recording once more, without drawing, through the same pipeline
// (ReplayController), on a thread of its own beside the window's replay: the force plot fills in
// as it goes, the assessment and its marks come at the end (they need the whole run: a step not
// done is known only then). While replaying it notes when what the report keeps only as totals
// happened (the largest force, the peak stress, the cut off the line, the clip applier's
// closings).
#pragma once

#include <cstddef>
#include <filesystem>
#include <functional>
#include <mutex>
#include <optional>
#include <stop_token>
#include <string>
#include <thread>
#include <vector>

#include <nlohmann/json.hpp>

#include "app/failure_marks.h"
#include "render/render_frame.h"

namespace serosa::replay {

using app::Failure;

/// The timeline so far.
struct TimelineData {
  double duration_s = 0.0;     ///< the recording's length, s
  std::uint64_t steps = 0;     ///< the recording's steps
  std::uint64_t computed = 0;  ///< steps replayed so far
  /// (bins) largest tool force on the tissue over each bin's steps, N; -1: not replayed yet
  std::vector<float> force_n;
  std::vector<render::TimelineMark> marks;  ///< the failed criteria's moments, in time order
  /// The run's "metrics", "procedure" and "assessment" blocks (as `serosa replay --headless`
  /// reports them), once done; null before, and without a metrics stage.
  nlohmann::json report;
  std::vector<Failure> failures;  ///< what the assessment failed on, in words (once done)
  bool done = false;              ///< replayed to the end (or stopped by an error)
  std::string error;              ///< why it stopped short of the end, when it did
};

/// Replays `recording` to its end or until `stop`, pooling the force into `bins` bins, and calls
/// `progress` every few hundred steps and at the end. Throws InputError when the file is not a
/// usable recording.
TimelineData compute_timeline(const std::filesystem::path& recording, std::size_t bins,
                              const std::stop_token& stop = {},
                              const std::function<void(const TimelineData&)>& progress = {});

/// The marks of `failed`: one per moment of each failed criterion, in time order.
[[nodiscard]] std::vector<render::TimelineMark> failure_timeline_marks(
    const std::vector<Failure>& failed);

/// The first mark later than `after_s`, wrapping round to the first; nullopt with no mark.
[[nodiscard]] std::optional<std::size_t> next_mark(const std::vector<render::TimelineMark>& marks,
                                                   double after_s);

/// The mark N jumps to from the replay's position `time_s`: while the replay is still before (or
/// at) the mark last jumped to, `current` (-1: none), the one after it; else the first later than
/// `time_s`, wrapping round; nullopt with no mark.
[[nodiscard]] std::optional<std::size_t> mark_to_jump_to(
    const std::vector<render::TimelineMark>& marks, int current, double time_s);

/// The mark P jumps to from `time_s` (the jump lands kJumpLeadS before its mark): the last one
/// whose landing point is more than half a second before `time_s`, wrapping round to the last;
/// nullopt with no mark.
[[nodiscard]] std::optional<std::size_t> mark_to_jump_back_to(
    const std::vector<render::TimelineMark>& marks, double time_s);

/// A jump lands this long before its mark, so that the instructor sees what led up to it, s.
inline constexpr double kJumpLeadS = 1.0;

/// compute_timeline on a thread of its own; stopped and joined when destroyed.
class TimelineBuilder {
 public:
  static constexpr std::size_t kBins = 400;

  explicit TimelineBuilder(std::filesystem::path recording);
  ~TimelineBuilder();
  TimelineBuilder(const TimelineBuilder&) = delete;
  TimelineBuilder& operator=(const TimelineBuilder&) = delete;

  /// A copy of what is known so far.
  [[nodiscard]] TimelineData data() const;

 private:
  mutable std::mutex m_mutex;
  TimelineData m_data;
  std::jthread m_thread;  // declared last: stopped and joined first
};

}  // namespace serosa::replay
