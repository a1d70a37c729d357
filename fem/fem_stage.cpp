#include "fem/fem_stage.h"

#include <omp.h>

#include <algorithm>
#include <utility>

#include "engine/sim_state.h"

namespace serosa::fem {

FemStage::FemStage(FemConfig config) : m_integrator(std::move(config)) {}

void FemStage::take_cuts(SimState& state) {
  if (!state.blocks.fem.stage_built) return;  // the first step builds everything anyway
  for (const CutEvent& cut : state.events.cuts) {
    if (cut.delta.version_before != m_seen_version) continue;  // seen, or not ours to follow
    m_integrator.update(state.mesh, cut.delta);
    m_seen_version = cut.delta.version_after;
    ++m_stats.updates;
  }
}

void FemStage::prepare(const StepContext& ctx, SimState& state) {
  m_integrator.bind(state.blocks.fem);
  if (state.blocks.fem.stage_built && m_seen_version == state.mesh.topology_version) return;
  if (m_integrator.config().solver.threads > 0)
    omp_set_num_threads(m_integrator.config().solver.threads);
  m_integrator.prepare(state.mesh, ctx.dt_s);
  m_seen_version = state.mesh.topology_version;
  state.blocks.fem.stage_built = true;
  ++m_stats.rebuilds;
}

void FemStage::adopt(SimState& state) {
  m_integrator.bind(state.blocks.fem);
  m_integrator.adopt(state.mesh);
  m_seen_version = state.mesh.topology_version;
}

void FemStage::step(const StepContext& ctx, SimState& state) {
  m_integrator.bind(state.blocks.fem);
  take_cuts(state);
  if (state.events.nodes_moved) m_integrator.restart_energy_balance();
  if (!state.blocks.fem.stage_built || m_seen_version != state.mesh.topology_version) {
    m_integrator.rebuild(state.mesh);
    m_seen_version = state.mesh.topology_version;
    state.blocks.fem.stage_built = true;
    ++m_stats.rebuilds;
  }
  if (m_integrator.config().solver.threads > 0)
    omp_set_num_threads(m_integrator.config().solver.threads);
  m_last = m_integrator.step(state.mesh, ctx.dt_s, state.events.external_force_n);
  ++m_stats.steps;
  const StepTrouble here{ctx.step, ctx.time_s, m_last.iterations, m_last.residual};
  const auto count = [&](bool trouble, std::uint64_t& n, std::optional<StepTrouble>& first) {
    if (!trouble) return;
    ++n;
    if (!first) first = here;
  };
  count(!m_last.solve_converged, m_stats.not_converged, m_stats.first_not_converged);
  m_stats.peak_energy_j = std::max(m_stats.peak_energy_j, m_last.energy_j);
  count(!m_last.applied, m_stats.rejected, m_stats.first_rejected);
  if (m_last.energy_gain) ++m_stats.energy_gains;
  count(m_last.energy_gain && !m_last_solve_converged, m_stats.energy_gains_after_capped_solve,
        m_stats.first_energy_gain);
  m_last_solve_converged = m_last.solve_converged;
  if (m_last.factor_refresh) ++m_stats.factor_refreshes;
  if (m_last.factor_patch) ++m_stats.factor_patches;
  m_stats.energy_removed_j += m_last.energy_removed_j;
}

}  // namespace serosa::fem
