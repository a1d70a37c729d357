#include "engine/runner.h"

#include <algorithm>
#include <stdexcept>

#include "engine/sim_state.h"

namespace serosa {

Runner::Runner(double dt_s) : m_dt_s(dt_s) {
  if (!(dt_s > 0.0)) throw std::invalid_argument("Runner: dt must be > 0");
}

void Runner::add(Slot slot, std::unique_ptr<Stage> stage) {
  if (!stage) throw std::invalid_argument("Runner: null stage");
  const auto after = std::upper_bound(m_entries.begin(), m_entries.end(), slot,
                                      [](Slot s, const Entry& e) { return s < e.slot; });
  StageTiming timing{std::string(stage->name()), 0.0, 0};
  m_entries.insert(after, Entry{slot, std::move(stage), std::move(timing)});
}

void Runner::run_slot(Slot slot, const StepContext& ctx, SimState& state) {
  for (Entry& e : m_entries) {
    if (e.slot != slot) continue;
    const auto t0 = std::chrono::steady_clock::now();
    e.stage->step(ctx, state);
    e.timing.total_s +=
        std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    ++e.timing.calls;
  }
}

// The whole solver step, in order. Each place reads what the earlier ones handed on in
// SimState::handoff and writes its own part (engine/sim_state.h).
void Runner::step(SimState& state) {
  const StepContext ctx{state.step, state.time_s, m_dt_s};
  run_slot(Slot::tools, ctx, state);
  run_slot(Slot::haptics, ctx, state);
  run_slot(Slot::contact, ctx, state);
  run_slot(Slot::fem, ctx, state);
  run_slot(Slot::cutting, ctx, state);
  run_slot(Slot::surface, ctx, state);
  run_slot(Slot::metrics, ctx, state);
  run_slot(Slot::record, ctx, state);
  ++state.step;
  // Time from the step count, not by accumulation, so long runs do not drift.
  state.time_s = static_cast<double>(state.step) * m_dt_s;
}

void Runner::run(SimState& state, std::uint64_t n) {
  for (std::uint64_t i = 0; i < n; ++i) step(state);
}

std::vector<StageTiming> Runner::timings() const {
  std::vector<StageTiming> t;
  t.reserve(m_entries.size());
  for (const Entry& e : m_entries) t.push_back(e.timing);
  return t;
}

}  // namespace serosa
