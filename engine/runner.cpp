#include "engine/runner.h"

#include <stdexcept>

#include "engine/sim_state.h"

namespace serosa {

Runner::Runner(double dt_s) : m_dt_s(dt_s) {
  if (!(dt_s > 0.0)) throw std::invalid_argument("Runner: dt must be > 0");
}

void Runner::add(std::unique_ptr<Stage> stage) {
  if (!stage) throw std::invalid_argument("Runner: null stage");
  m_timings.push_back({std::string(stage->name()), 0.0, 0});
  m_stages.push_back(std::move(stage));
}

void Runner::step(SimState& state) {
  const StepContext ctx{state.step, state.time_s, m_dt_s};
  for (std::size_t i = 0; i < m_stages.size(); ++i) {
    const auto t0 = std::chrono::steady_clock::now();
    m_stages[i]->step(ctx, state);
    const auto t1 = std::chrono::steady_clock::now();
    m_timings[i].total_s += std::chrono::duration<double>(t1 - t0).count();
    ++m_timings[i].calls;
  }
  ++state.step;
  // Time from the step count, not by accumulation, so long runs do not drift.
  state.time_s = static_cast<double>(state.step) * m_dt_s;
}

void Runner::run(SimState& state, std::uint64_t n) {
  for (std::uint64_t i = 0; i < n; ++i) step(state);
}

}  // namespace serosa
