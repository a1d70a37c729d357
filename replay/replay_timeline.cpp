#include "replay/replay_timeline.h"

#include <algorithm>
#include <limits>
#include <utility>

#include "app/assessment_report.h"
#include "app/compose.h"
#include "metrics/metrics_stage.h"
#include "replay/replay_controller.h"

namespace serosa::replay {

using namespace serosa::app;  // the driver, the composition and the window's parts
namespace {

constexpr std::uint64_t kProgressEvery = 200;  // steps between progress calls

// Follows the metrics from step to step: the force plot's value, and when what the report keeps
// only as totals happened.
class EventWatch {
 public:
  EventWatch(const Scene& scene, const MetricsStage& metrics)
      : m_scene(scene), m_metrics(metrics), m_jaw(scene.tools.size(), 0.0) {}

  // The tools' largest force this step, N.
  float after_step(double t_s, const SimState& state) {
    double largest = 0.0;
    for (std::size_t i = 0; i < m_scene.tools.size(); ++i) {
      const double f = m_metrics.load_n(i);
      largest = std::max(largest, f);
      if (f > 0.0 && f >= m_metrics.force_max_n(i))
        m_events.force_max_at_s[m_scene.tools[i].name] = t_s;
      if (f > m_metrics.force_limit_n() && m_events.force_over_at_s < 0.0)
        m_events.force_over_at_s = t_s;
      if (i < state.tools.size()) watch_clip_applier(i, t_s, state.tools[i].jaw_rad);
    }
    if (m_metrics.peak_stress_pa() > m_peak) m_events.peak_stress_at_s = t_s;
    m_peak = m_metrics.peak_stress_pa();
    const double cut = m_metrics.cut_volume_m3();
    if (cut > m_cut && m_events.first_cut_at_s < 0.0) m_events.first_cut_at_s = t_s;
    m_cut = cut;
    const double added = m_metrics.collateral_m3() - m_collateral;
    if (added > m_most_collateral) {
      m_most_collateral = added;
      m_events.collateral_at_s = t_s;
    }
    m_collateral = m_metrics.collateral_m3();
    m_events.end_s = t_s;
    return static_cast<float>(largest);
  }

  [[nodiscard]] const RunEvents& events() const { return m_events; }

 private:
  // A clip applier's jaws closing (from open) is where its clip went, or failed to.
  void watch_clip_applier(std::size_t i, double t_s, double jaw_rad) {
    if (m_scene.tools[i].kind != ToolKind::kClipApplier) return;
    constexpr double kOpen = 0.15, kClosed = 0.05;  // rad
    if (jaw_rad > kOpen) m_jaw[i] = jaw_rad;
    if (jaw_rad < kClosed && m_jaw[i] > kOpen) {
      m_events.clip_closed_at_s.push_back(t_s);
      m_jaw[i] = 0.0;
    }
  }

  const Scene& m_scene;
  const MetricsStage& m_metrics;
  std::vector<double> m_jaw;  // (tools) a clip applier's opening since it last closed, rad
  RunEvents m_events;
  double m_peak = 0.0, m_cut = 0.0, m_collateral = 0.0, m_most_collateral = 0.0;
};

// The report's metric blocks and the failures once the replay reached the recording's end.
void assess(const ReplayController& replay, const EventWatch& watch, TimelineData& d) {
  nlohmann::json report;
  add_metrics_blocks(report, replay.scene(), replay.composition().metrics, replay.state().mesh,
                     replay.group_names());
  RunEvents events = watch.events();
  events.end_s = replay.time_s();
  d.failures = failures(report, events);
  d.marks = failure_timeline_marks(d.failures);
  d.report = std::move(report);
}

}  // namespace

TimelineData compute_timeline(const std::filesystem::path& recording, std::size_t bins,
                              const std::stop_token& stop,
                              const std::function<void(const TimelineData&)>& progress) {
  ReplayControllerOptions options;
  options.snapshot_every_s = std::numeric_limits<double>::max();  // forward only: none needed
  ReplayController replay(recording, options);
  TimelineData d;
  d.steps = replay.num_steps();
  d.duration_s = replay.duration_s();
  d.force_n.assign(std::max<std::size_t>(bins, 1), -1.0f);
  const MetricsStage* metrics = replay.composition().metrics;
  if (metrics == nullptr) {  // a scene without metrics: nothing to plot or mark
    d.done = true;
    if (progress) progress(d);
    return d;
  }
  EventWatch watch(replay.scene(), *metrics);
  try {
    while (!stop.stop_requested() && replay.step_forward()) {
      const float force = watch.after_step(replay.time_s(), replay.state());
      const std::size_t bin =
          std::min<std::size_t>(d.computed * d.force_n.size() / std::max<std::uint64_t>(d.steps, 1),
                                d.force_n.size() - 1);
      d.force_n[bin] = std::max(d.force_n[bin], force);
      ++d.computed;
      if (progress && d.computed % kProgressEvery == 0) progress(d);
    }
    if (!stop.stop_requested()) assess(replay, watch, d);
  } catch (const std::exception& e) {
    d.error = e.what();  // what was computed stays shown
  }
  d.done = true;
  if (progress) progress(d);
  return d;
}

std::vector<render::TimelineMark> failure_timeline_marks(const std::vector<Failure>& failed) {
  std::vector<render::TimelineMark> marks;
  for (const Failure& f : failed)
    for (const double t : f.at_s) marks.push_back({t, f.words, f.criterion});
  std::stable_sort(marks.begin(), marks.end(),
                   [](const auto& a, const auto& b) { return a.time_s < b.time_s; });
  return marks;
}

std::optional<std::size_t> next_mark(const std::vector<render::TimelineMark>& marks,
                                     double after_s) {
  if (marks.empty()) return std::nullopt;
  for (std::size_t k = 0; k < marks.size(); ++k)
    if (marks[k].time_s > after_s) return k;
  return 0;
}

std::optional<std::size_t> mark_to_jump_to(const std::vector<render::TimelineMark>& marks,
                                           int current, double time_s) {
  const auto n = static_cast<int>(marks.size());
  if (current >= 0 && current < n && time_s <= marks[static_cast<std::size_t>(current)].time_s)
    return static_cast<std::size_t>((current + 1) % n);
  return next_mark(marks, time_s);
}

std::optional<std::size_t> mark_to_jump_back_to(const std::vector<render::TimelineMark>& marks,
                                                double time_s) {
  if (marks.empty()) return std::nullopt;
  constexpr double kSlackS = 0.5;  // a jump just taken lands here: P goes one further back
  for (std::size_t k = marks.size(); k-- > 0;)
    if (std::max(marks[k].time_s - kJumpLeadS, 0.0) < time_s - kSlackS) return k;
  return marks.size() - 1;
}

TimelineBuilder::TimelineBuilder(std::filesystem::path recording)
    : m_thread([this, file = std::move(recording)](const std::stop_token& stop) {
        try {
          compute_timeline(file, kBins, stop, [this](const TimelineData& d) {
            const std::lock_guard lock(m_mutex);
            m_data = d;
          });
        } catch (const std::exception& e) {
          const std::lock_guard lock(m_mutex);
          m_data.done = true;
          m_data.error = e.what();
        }
      }) {}

TimelineBuilder::~TimelineBuilder() {
  m_thread.request_stop();
  if (m_thread.joinable()) m_thread.join();
}

TimelineData TimelineBuilder::data() const {
  const std::lock_guard lock(m_mutex);
  return m_data;
}

}  // namespace serosa::replay
