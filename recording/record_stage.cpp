#include "recording/record_stage.h"

#include <stdexcept>

#include "engine/sim_state.h"

namespace serosa::recording {

void RecordStage::step(const StepContext& ctx, SimState& state) {
  if (m_writer == nullptr) return;
  m_writer->record_inputs(ctx.step, state.tools);
  if (hashed_step(ctx.step, m_hash_every)) m_writer->record_hash(ctx.step, state_hash(state));
}

void ReplayInputStage::set_live(std::size_t i, const ToolState& input) {
  if (!m_live) throw std::logic_error("ReplayInputStage: not live");
  m_live->at(i) = input;
}

void ReplayInputStage::step(const StepContext& ctx, SimState& state) {
  if (m_live) {
    state.tools = *m_live;
    return;
  }
  const std::vector<ToolState>& in = m_inputs.at(ctx.step);
  if (in.size() != state.tools.size())
    throw std::out_of_range("recorded tool count differs from the scene's");
  state.tools = in;
}

void VerifyStage::step(const StepContext& ctx, SimState& state) {
  const auto it = m_hashes.find(ctx.step);
  if (it == m_hashes.end() && !m_every_step) return;
  m_last = state_hash(state);
  if (it == m_hashes.end()) return;
  ++m_checked;
  if (*m_last != it->second && !m_divergence)
    m_divergence = Divergence{ctx.step, it->second, *m_last};
}

}  // namespace serosa::recording
