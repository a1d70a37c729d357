#include "fem/fem_stage.h"

#include <omp.h>

#include <utility>

#include "engine/sim_state.h"

namespace serosa::fem {

FemStage::FemStage(FemConfig config) : m_integrator(std::move(config)) {}

void FemStage::set_external_forces(std::span<const Vec3> f) { m_f_ext.assign(f.begin(), f.end()); }

void FemStage::on_topology_change(SimState& state, const TopologyDelta& delta) {
  if (!m_built) return;  // the first step builds everything anyway
  m_integrator.update(state.mesh, delta);
  m_seen_version = state.mesh.topology_version;
  ++m_stats.updates;
}

void FemStage::step(const StepContext& ctx, SimState& state) {
  if (!m_built || m_seen_version != state.mesh.topology_version) {
    m_integrator.rebuild(state.mesh);
    m_seen_version = state.mesh.topology_version;
    m_built = true;
    ++m_stats.rebuilds;
  }
  if (m_integrator.config().solver.threads > 0)
    omp_set_num_threads(m_integrator.config().solver.threads);
  m_last = m_integrator.step(state.mesh, ctx.dt_s, m_f_ext);
  ++m_stats.steps;
  if (!m_last.converged) ++m_stats.not_converged;
  if (!m_last.applied) ++m_stats.rejected;
  if (m_last.energy_gain) ++m_stats.energy_gains;
  if (m_last.factor_refresh) ++m_stats.factor_refreshes;
  m_stats.energy_removed_j += m_last.energy_removed_j;
}

}  // namespace serosa::fem
