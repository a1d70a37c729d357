// The procedure's run split at its steps: what each step cost the trainee. A step's share runs
// from the moment the step done before it (in time) was done, or from the start, to the moment it
// was done; steps done in the same solver step share one split (the first gets it, the others
// none). What follows the last step done is kept apart (`after_last_step`): a run that stops short
// shows where its time went.
//   duration_s              simulated time of the split, s
//   path_length_m[tool]     each instrument tip's path in it, m; the hand instruments' sum
//   idle_time_s             time in it in which no hand instrument moved (metrics_stage.h), s
#pragma once

#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

namespace serosa {
class StateWriter;
class StateReader;
}  // namespace serosa

namespace serosa::metrics {

struct StepSplit {
  double duration_s = 0.0;     ///< s
  std::vector<double> path_m;  ///< (tools) m
  double idle_s = 0.0;         ///< s
  [[nodiscard]] double hand_path_m(const std::vector<std::uint8_t>& hand) const;
};

class StepSplits {
 public:
  StepSplits() = default;
  /// steps: how many steps the procedure has; tools: each tool's name (scene order); hand: (tools)
  /// 1 for a hand instrument (not the endoscope).
  StepSplits(std::size_t steps, std::vector<std::string> tools, std::vector<std::uint8_t> hand);

  [[nodiscard]] bool active() const noexcept { return !m_done.empty(); }
  /// Adds one solver step: each tip's move (m, (tools)), whether every hand was idle, its dt (s).
  void add(const std::vector<double>& moved, bool idle, double dt_s);
  /// Step `step` was just done: the open split is its own, and a new one opens.
  void close(std::size_t step);

  [[nodiscard]] const StepSplit& split(std::size_t step) const { return m_done[step]; }
  [[nodiscard]] const StepSplit& open() const noexcept { return m_open; }
  /// The hand instruments' path in the split, m.
  [[nodiscard]] double hand_path_m(const StepSplit& s) const { return s.hand_path_m(m_hand); }

  /// Adds each split's figures to metrics["procedure"]["steps"][i], and the open one as
  /// metrics["procedure"]["after_last_step"].
  void report(nlohmann::json& metrics) const;

  void save(StateWriter& out) const;
  void restore(StateReader& in);

 private:
  [[nodiscard]] nlohmann::json json(const StepSplit& s) const;

  std::vector<std::string> m_tools;
  std::vector<std::uint8_t> m_hand;  // (tools)
  std::vector<StepSplit> m_done;     // (steps) each step's split; zero until it is done
  StepSplit m_open;                  // since the last step done
};

}  // namespace serosa::metrics
