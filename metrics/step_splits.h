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

#include "engine/bound_block.h"
#include "engine/metrics_block.h"

namespace serosa::metrics {

using serosa::StepSplit;

class StepSplits {
 public:
  StepSplits() = default;
  /// steps: how many steps the procedure has; tools: each tool's name (scene order); hand: (tools)
  /// 1 for a hand instrument (not the endoscope).
  StepSplits(std::size_t steps, std::vector<std::string> tools, std::vector<std::uint8_t> hand);

  [[nodiscard]] bool active() const noexcept { return !m_b->done.empty(); }
  /// Adds one solver step: each tip's move (m, (tools)), whether every hand was idle, its dt (s).
  void add(const std::vector<double>& moved, bool idle, double dt_s);
  /// Step `step` was just done: the open split is its own, and a new one opens.
  void close(std::size_t step);

  [[nodiscard]] const StepSplit& split(std::size_t step) const { return m_b->done[step]; }
  [[nodiscard]] const StepSplit& open() const noexcept { return m_b->open; }
  /// The hand instruments' path in the split, m.
  [[nodiscard]] double hand_path_m(const StepSplit& s) const;

  /// Adds each split's figures to metrics["procedure"]["steps"][i], and the open one as
  /// metrics["procedure"]["after_last_step"].
  void report(nlohmann::json& metrics) const;

  /// Reads and writes the SimState block `b` from now on (engine/bound_block.h).
  void bind(SplitsBlock& b) noexcept { m_b.bind(b); }
  /// The zero block it starts a state's from.
  [[nodiscard]] const SplitsBlock& unbound_block() const noexcept { return m_b.unbound(); }

 private:
  [[nodiscard]] nlohmann::json json(const StepSplit& s) const;

  std::vector<std::string> m_tools;
  std::vector<std::uint8_t> m_hand;  // (tools)
  BoundBlock<SplitsBlock> m_b;       // its block of the state
};

}  // namespace serosa::metrics
