#include "metrics/step_splits.h"

#include <algorithm>
#include <utility>

#include "engine/state_codec.h"

namespace serosa::metrics {

double StepSplit::hand_path_m(const std::vector<std::uint8_t>& hand) const {
  double sum = 0.0;
  for (std::size_t i = 0; i < path_m.size() && i < hand.size(); ++i)
    if (hand[i] != 0) sum += path_m[i];
  return sum;
}

StepSplits::StepSplits(std::size_t steps, std::vector<std::string> tools,
                       std::vector<std::uint8_t> hand)
    : m_tools(std::move(tools)), m_hand(std::move(hand)) {
  m_open.path_m.assign(m_tools.size(), 0.0);
  m_done.assign(steps, m_open);
}

void StepSplits::add(const std::vector<double>& moved, bool idle, double dt_s) {
  if (!active()) return;
  m_open.duration_s += dt_s;
  if (idle) m_open.idle_s += dt_s;
  for (std::size_t i = 0; i < moved.size() && i < m_open.path_m.size(); ++i)
    m_open.path_m[i] += moved[i];
}

void StepSplits::close(std::size_t step) {
  if (step >= m_done.size()) return;
  m_done[step] = m_open;
  m_open.duration_s = 0.0;
  m_open.idle_s = 0.0;
  std::fill(m_open.path_m.begin(), m_open.path_m.end(), 0.0);
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
  for (std::size_t i = 0; i < m_done.size() && i < steps.size(); ++i)
    steps[i].update(json(m_done[i]));
  metrics["procedure"]["after_last_step"] = json(m_open);
}

void StepSplits::save(StateWriter& out) const {
  if (!active()) return;
  auto write = [&](const StepSplit& s) {
    out.f64(s.duration_s);
    out.f64(s.idle_s);
    out.array(s.path_m);
  };
  for (const StepSplit& s : m_done) write(s);
  write(m_open);
}

void StepSplits::restore(StateReader& in) {
  if (!active()) return;
  auto read = [&](StepSplit& s) {
    s.duration_s = in.f64();
    s.idle_s = in.f64();
    in.array(s.path_m);
    if (s.path_m.size() != m_tools.size()) in.fail("another number of tools than the scene's");
  };
  for (StepSplit& s : m_done) read(s);
  read(m_open);
}

}  // namespace serosa::metrics
