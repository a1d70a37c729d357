// The replay's metric timeline (instructors): the tools' force on the tissue over the whole
// recording and the errors marked where they happened, so that one key jumps to each.
//
// Computed by replaying the recording once more, without drawing, through the same pipeline
// (ReplayController), on a thread of its own beside the window's replay: the window shows the
// timeline as it fills in. The errors are what the metrics see as they happen:
// - a tool pressing harder than the scene's force_limit ("grasper over 5 N"), once per time it
//   crosses the limit;
// - a cut that takes tissue outside the band around the planned cut line ("cut 1.2 mm3 off the
//   planned line"), once per step that adds such collateral.
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

#include "render/render_frame.h"

namespace serosa::app {

/// The timeline so far.
struct TimelineData {
  double duration_s = 0.0;     ///< the recording's length, s
  std::uint64_t steps = 0;     ///< the recording's steps
  std::uint64_t computed = 0;  ///< steps replayed so far
  /// (bins) largest tool force on the tissue over each bin's steps, N; -1: not replayed yet
  std::vector<float> force_n;
  std::vector<render::TimelineMark> marks;  ///< errors, in time order
  bool done = false;                        ///< replayed to the end (or stopped by an error)
  std::string error;                        ///< why it stopped short of the end, when it did
};

/// Replays `recording` to its end or until `stop`, pooling the force into `bins` bins, and calls
/// `progress` every few hundred steps and at the end. Throws InputError when the file is not a
/// usable recording.
TimelineData compute_timeline(const std::filesystem::path& recording, std::size_t bins,
                              const std::stop_token& stop = {},
                              const std::function<void(const TimelineData&)>& progress = {});

/// The first mark later than `after_s`, wrapping round to the first; nullopt with no mark.
[[nodiscard]] std::optional<std::size_t> next_mark(const std::vector<render::TimelineMark>& marks,
                                                   double after_s);

/// The mark N jumps to from the replay's position `time_s`: while the replay is still before (or
/// at) the mark last jumped to, `current` (-1: none), the one after it; else the first later than
/// `time_s`, wrapping round; nullopt with no mark.
[[nodiscard]] std::optional<std::size_t> mark_to_jump_to(
    const std::vector<render::TimelineMark>& marks, int current, double time_s);

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

}  // namespace serosa::app
