// Runner: drives the stages app composed, in order, one solver step at a time, and times each.
// This is the synchronous core; the haptics and render threads attach to it through the
// hand-off primitives (seqlock.h, triple_buffer.h).
#pragma once

#include <chrono>
#include <memory>
#include <string>
#include <vector>

#include "engine/stage.h"

namespace serosa {

struct SimState;

struct StageTiming {
  std::string name;
  double total_s = 0.0;  ///< wall time spent in this stage over all steps, s
  std::uint64_t calls = 0;
};

class Runner {
 public:
  explicit Runner(double dt_s);

  void add(std::unique_ptr<Stage> stage);
  /// Takes one solver step: calls every stage in order, then advances time and step count.
  void step(SimState& state);
  /// Takes n steps.
  void run(SimState& state, std::uint64_t n);

  [[nodiscard]] double dt_s() const noexcept { return m_dt_s; }
  [[nodiscard]] const std::vector<StageTiming>& timings() const noexcept { return m_timings; }
  [[nodiscard]] std::size_t num_stages() const noexcept { return m_stages.size(); }

 private:
  double m_dt_s;
  std::vector<std::unique_ptr<Stage>> m_stages;
  std::vector<StageTiming> m_timings;  // parallel to m_stages
};

}  // namespace serosa
