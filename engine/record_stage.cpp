#include "engine/record_stage.h"

#include <stdexcept>

#include "engine/sim_state.h"

namespace serosa::recording {

void RecordStage::step(const StepContext& ctx, SimState& state) {
  m_writer.record_inputs(ctx.step, state.tools);
  if (hashed_step(ctx.step, m_hash_every)) m_writer.record_hash(ctx.step, state_hash(state));
}

void ReplayInputStage::step(const StepContext& ctx, SimState& state) {
  const std::vector<ToolState>& in = m_inputs.at(ctx.step);
  if (in.size() != state.tools.size())
    throw std::out_of_range("recorded tool count differs from the scene's");
  state.tools = in;
}

void VerifyStage::step(const StepContext& ctx, SimState& state) {
  const auto it = m_hashes.find(ctx.step);
  if (it == m_hashes.end()) return;
  ++m_checked;
  const std::uint64_t h = state_hash(state);
  if (h != it->second && !m_divergence) m_divergence = Divergence{ctx.step, it->second, h};
}

}  // namespace serosa::recording
