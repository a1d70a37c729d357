#include "metrics/step_splits.h"

#include <algorithm>
#include <utility>

namespace serosa::metrics {

double StepSplits::hand_path_m(const StepSplit& s) const {
  double sum = 0.0;
  for (std::size_t i = 0; i < s.path_m.size() && i < m_hand.size(); ++i)
    if (m_hand[i] != 0) sum += s.path_m[i];
  return sum;
}

StepSplits::StepSplits(std::size_t steps, std::vector<std::string> tools,
                       std::vector<std::uint8_t> hand)
    : m_tools(std::move(tools)), m_hand(std::move(hand)) {
  m_b->open.path_m.assign(m_tools.size(), 0.0);
  m_b->done.assign(steps, m_b->open);
}

void StepSplits::add(const std::vector<double>& moved, bool idle, double dt_s) {
  if (!active()) return;
  m_b->open.duration_s += dt_s;
  if (idle) m_b->open.idle_s += dt_s;
  for (std::size_t i = 0; i < moved.size() && i < m_b->open.path_m.size(); ++i)
    m_b->open.path_m[i] += moved[i];
}

void StepSplits::close(std::size_t step) {
  if (step >= m_b->done.size()) return;
  m_b->done[step] = m_b->open;
  m_b->open.duration_s = 0.0;
  m_b->open.idle_s = 0.0;
  std::fill(m_b->open.path_m.begin(), m_b->open.path_m.end(), 0.0);
}

nlohmann::json StepSplits::json(const StepSplit& s) const {
  nlohmann::json j{{"duration_s", s.duration_s}, {"idle_time_s", s.idle_s}};
  j["path_length_m"]["hands"] = hand_path_m(s);
  for (std::size_t i = 0; i < m_tools.size() && i < s.path_m.size(); ++i)
    j["path_length_m"][m_tools[i]] = s.path_m[i];
  return j;
}

void StepSplits::report(nlohmann::json& metrics) const {
  if (!active() || !metrics.contains("procedure")) return;
  nlohmann::json& steps = metrics["procedure"]["steps"];
  for (std::size_t i = 0; i < m_b->done.size() && i < steps.size(); ++i)
    steps[i].update(json(m_b->done[i]));
  metrics["procedure"]["after_last_step"] = json(m_b->open);
}

}  // namespace serosa::metrics
