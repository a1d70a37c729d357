#include "app/replay_timeline.h"

#include <algorithm>
#include <cstdio>
#include <limits>
#include <utility>

#include "app/compose.h"
#include "app/replay_controller.h"
#include "metrics/metrics_stage.h"

namespace serosa::app {
namespace {

constexpr std::uint64_t kProgressEvery = 200;  // steps between progress calls

// Follows the metrics from step to step and marks the errors as they happen.
class ErrorWatch {
 public:
  ErrorWatch(const Scene& scene, const MetricsStage& metrics)
      : m_scene(scene), m_metrics(metrics), m_over(scene.tools.size(), 0) {}

  // The tools' largest force this step, N; marks what went wrong in it.
  float after_step(double t_s, std::vector<render::TimelineMark>& marks) {
    double largest = 0.0;
    const double limit = m_metrics.force_limit_n();
    for (std::size_t i = 0; i < m_scene.tools.size(); ++i) {
      const double f = m_metrics.load_n(i);
      largest = std::max(largest, f);
      const bool over = f > limit;
      if (over && m_over[i] == 0) {
        char what[96];
        std::snprintf(what, sizeof what, " over %.3g N", limit);
        marks.push_back({t_s, m_scene.tools[i].name + what});
      }
      m_over[i] = over ? 1 : 0;
    }
    const double collateral = m_metrics.collateral_m3();
    if (collateral > m_collateral) {
      char what[96];
      std::snprintf(what, sizeof what, "cut %.3g mm3 off the planned line",
                    (collateral - m_collateral) * 1e9);
      marks.push_back({t_s, what});
    }
    m_collateral = collateral;
    return static_cast<float>(largest);
  }

 private:
  const Scene& m_scene;
  const MetricsStage& m_metrics;
  std::vector<std::uint8_t> m_over;  // (tools) over the limit last step
  double m_collateral = 0.0;
};

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
  ErrorWatch watch(replay.scene(), *metrics);
  try {
    while (!stop.stop_requested() && replay.step_forward()) {
      const float force = watch.after_step(replay.time_s(), d.marks);
      const std::size_t bin =
          std::min<std::size_t>(d.computed * d.force_n.size() / std::max<std::uint64_t>(d.steps, 1),
                                d.force_n.size() - 1);
      d.force_n[bin] = std::max(d.force_n[bin], force);
      ++d.computed;
      if (progress && d.computed % kProgressEvery == 0) progress(d);
    }
  } catch (const std::exception& e) {
    d.error = e.what();  // what was computed stays shown
  }
  d.done = true;
  if (progress) progress(d);
  return d;
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

}  // namespace serosa::app
