#include "replay/branch_assessment.h"

#include <spdlog/spdlog.h>

#include <algorithm>
#include <array>
#include <fstream>
#include <stdexcept>
#include <string_view>

#include "app/assessment_report.h"
#include "app/compose.h"
#include "app/session_summary.h"
#include "replay/replay_controller.h"
#include "replay/replay_timeline.h"

namespace serosa::replay {

using namespace serosa::app;  // the driver, the composition and the window's parts
namespace {

// The criteria an error fails for good the moment it happens.
constexpr std::array<std::string_view, 5> kEventCriteria = {"bleeding_events", "thermal_injuries",
                                                            "tears", "specimens_dropped",
                                                            "transections_above_securing"};

bool is_event(const std::string& criterion) {
  return std::find(kEventCriteria.begin(), kEventCriteria.end(), criterion) != kEventCriteria.end();
}

}  // namespace

nlohmann::json report_so_far(const ReplayController& replay) {
  nlohmann::json report;
  add_metrics_blocks(report, replay.scene(), replay.composition().metrics, replay.state().mesh,
                     replay.group_names());
  return report;
}

std::vector<render::TimelineMark> branch_marks(const std::vector<render::TimelineMark>& original,
                                               double branch_s, const nlohmann::json& report) {
  std::vector<render::TimelineMark> marks;
  for (const render::TimelineMark& m : original)
    if (m.time_s < branch_s) marks.push_back(m);
  RunEvents none;  // the events' own times come from the report's lists
  std::vector<Failure> own = failures(report, none);
  std::erase_if(own, [](const Failure& f) { return !is_event(f.criterion); });
  for (render::TimelineMark& m : failure_timeline_marks(own))
    if (m.time_s >= branch_s) marks.push_back(std::move(m));
  return marks;
}

void BranchDebrief::update(const ReplayController& replay,
                           const std::vector<render::TimelineMark>& original, bool now) {
  const auto t = std::chrono::steady_clock::now();
  if (!now && m_last && t - *m_last < std::chrono::seconds(1)) return;
  m_last = t;
  const nlohmann::json report = report_so_far(replay);
  const double branch_s = static_cast<double>(replay.branch_step().value_or(0)) * replay.dt_s();
  m_marks = branch_marks(original, branch_s, report);
  if (!report.contains("assessment")) return;
  m_summary = session_summary(report);
  m_summary->title = "Branch so far: " + m_summary->title;
}

nlohmann::json finish_branch(ReplayController& replay, const std::filesystem::path& recording) {
  replay.end_branch();
  nlohmann::json report = report_so_far(replay);
  report["recording"] = recording.string();
  report["branch_step"] = replay.branch_step().value_or(0);
  report["steps"] = replay.steps_taken();
  std::filesystem::path file = recording;
  file.replace_extension(".json");
  std::ofstream out(file);
  out << report.dump(2) << "\n";
  if (!out) throw std::runtime_error("cannot write the branch's report " + file.string());
  spdlog::info("replay: branch of {} steps recorded (from step {}) into {}; its report: {}",
               replay.steps_taken(), replay.branch_step().value_or(0), recording.string(),
               file.string());
  return report;
}

}  // namespace serosa::replay
