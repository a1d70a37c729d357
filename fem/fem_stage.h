// FemStage: the "fem" stage of the solver pipeline (engine/stage.h). Each step advances
// SimState::mesh by one implicit corotational step (fem/implicit_integrator.h). It owns the
// integrator's caches; the FEM model (FemConfig) is fixed at construction.
#pragma once

#include <cstdint>
#include <span>
#include <string_view>
#include <vector>

#include "engine/stage.h"
#include "engine/topology_delta.h"
#include "fem/fem_config.h"
#include "fem/implicit_integrator.h"

namespace serosa::fem {

/// Counters over the stage's life (warnings are counted, never thrown).
struct FemStageStats {
  std::uint64_t steps = 0;          ///< steps taken
  std::uint64_t not_converged = 0;  ///< steps whose linear solve stopped above tolerance
  std::uint64_t rejected = 0;       ///< steps not applied (non-finite or diverged solve)
  std::uint64_t rebuilds = 0;       ///< full precomputes (first step, unseen topology changes)
  std::uint64_t updates = 0;        ///< incremental updates from TopologyDeltas
  /// Steps whose previous step gained energy (StepStatus::energy_gain: a capped solve injected it)
  std::uint64_t energy_gains = 0;
  /// Kinetic energy taken back out over those (SolverSettings::remove_energy_gain), J
  double energy_removed_j = 0.0;
  /// pcg_lagged: factorizations of the system matrix asked for (StepStatus::factor_refresh)
  std::uint64_t factor_refreshes = 0;
};

class FemStage final : public Stage {
 public:
  explicit FemStage(FemConfig config);

  [[nodiscard]] std::string_view name() const noexcept override { return "fem"; }
  /// One implicit step of length ctx.dt_s on state.mesh, with the external forces last set.
  void step(const StepContext& ctx, SimState& state) override;

  /// External node forces (n), N, applied from the next step on (tool contact, grasping); an
  /// empty span clears them. Sizes other than the node count are ignored at step time.
  void set_external_forces(std::span<const Vec3> f);
  /// Tells the stage about a topology change already applied to `state.mesh`, so that it
  /// updates only the affected elements (cutting publishes the delta between steps).
  void on_topology_change(SimState& state, const TopologyDelta& delta);
  /// Tells the stage that the caller set x or v of some nodes since the last step (a grasper
  /// moving the nodes it holds): that is the caller's work, not a gain of the last solve, so
  /// the next step's divergence guard skips its energy check (ImplicitIntegrator::
  /// restart_energy_balance) instead of flagging it and starting the solve cold.
  void nodes_moved_by_caller() { m_integrator.restart_energy_balance(); }

  [[nodiscard]] const StepStatus& last_status() const noexcept { return m_last; }
  [[nodiscard]] const FemStageStats& stats() const noexcept { return m_stats; }
  [[nodiscard]] const ImplicitIntegrator& integrator() const noexcept { return m_integrator; }

 private:
  ImplicitIntegrator m_integrator;
  std::vector<Vec3> m_f_ext;  // (n) or empty
  StepStatus m_last;
  FemStageStats m_stats;
  std::uint64_t m_seen_version = 0;
  bool m_built = false;
};

}  // namespace serosa::fem
