// FemStage: the "fem" stage of the solver pipeline (engine/stage.h). Each step advances
// SimState::mesh by one implicit corotational step (fem/implicit_integrator.h). It owns the
// integrator's caches; the FEM model (FemConfig) is fixed at construction. It reads what earlier
// stages handed over in SimState::events: the cuts of the previous step (their deltas update the
// integrator incrementally), the external forces and whether held nodes were moved.
#pragma once

#include <cstdint>
#include <optional>
#include <span>
#include <string_view>
#include <vector>

#include "engine/stage.h"
#include "engine/topology_delta.h"
#include "fem/fem_config.h"
#include "fem/implicit_integrator.h"

namespace serosa::fem {

/// A step whose solve was not what the scene asked for.
struct StepTrouble {
  std::uint64_t step = 0;  ///< its index (0-based)
  double time_s = 0.0;     ///< simulated time at its start, s
  int iterations = 0;      ///< CG iterations of its solve
  double residual = 0.0;   ///< relative residual the solve stopped at
};

/// Counters over the stage's life (warnings are counted, never thrown).
struct FemStageStats {
  std::uint64_t steps = 0;  ///< steps taken
  /// steps whose linear solve stopped above tolerance (StepStatus::solve_converged false)
  std::uint64_t not_converged = 0;
  std::uint64_t rejected = 0;  ///< steps not applied (non-finite or diverged solve)
  std::uint64_t rebuilds = 0;  ///< full precomputes (first step, unseen topology changes)
  std::uint64_t updates = 0;   ///< incremental updates from TopologyDeltas
  /// Steps whose previous step gained energy (StepStatus::energy_gain: a capped solve injected it)
  std::uint64_t energy_gains = 0;
  /// Of those, the steps whose previous solve had stopped above its tolerance: energy a capped
  /// solve injected. (The others are the corotational model's own small imbalance, a frozen
  /// rotation over a step or an explicit contact force, which the guard takes back out.)
  std::uint64_t energy_gains_after_capped_solve = 0;
  /// Kinetic energy taken back out over those (SolverSettings::remove_energy_gain), J
  double energy_removed_j = 0.0;
  /// The largest mechanical energy (kinetic + corotated elastic) a step started from, J: the
  /// scale the energy taken out is measured against
  double peak_energy_j = 0.0;
  /// pcg_lagged: factorizations of the system matrix asked for (StepStatus::factor_refresh)
  std::uint64_t factor_refreshes = 0;
  /// pcg_lagged: steps whose changed rows (a cut, a grasp, a release) got a factor of their own
  /// (StepStatus::factor_patch)
  std::uint64_t factor_patches = 0;
  /// The first step of each kind of trouble, as it happened: what a warning names.
  std::optional<StepTrouble> first_not_converged;
  std::optional<StepTrouble> first_energy_gain;  ///< after a capped solve
  std::optional<StepTrouble> first_rejected;
};

class FemStage final : public Stage {
 public:
  explicit FemStage(FemConfig config);

  [[nodiscard]] std::string_view name() const noexcept override { return "fem"; }
  /// One implicit step of length ctx.dt_s on state.mesh: first the cuts handed over since the
  /// last step (incremental updates), then the solve with events.external_force_n (ignored
  /// unless it holds one force per node). events.nodes_moved: the caller set x or v of some
  /// nodes (a grasper moving those it holds), which is its work, not a gain of the last solve,
  /// so the divergence guard skips its energy check (ImplicitIntegrator::restart_energy_balance)
  /// instead of flagging it and starting the solve cold.
  void step(const StepContext& ctx, SimState& state) override;
  /// The structure and the first factor (ImplicitIntegrator::prepare), before the first step.
  void prepare(const StepContext& ctx, SimState& state) override;
  /// The integrator's part of the state is SimState::blocks.fem; a restored one is checked
  /// against the mesh and the caches (elements, pattern, factors) are rebuilt for it.
  void adopt(SimState& state) override;

  [[nodiscard]] const StepStatus& last_status() const noexcept { return m_last; }
  [[nodiscard]] const FemStageStats& stats() const noexcept { return m_stats; }
  [[nodiscard]] const ImplicitIntegrator& integrator() const noexcept { return m_integrator; }

 private:
  /// The cuts in state.events that this stage has not seen, in order; a rebuild if they do not
  /// follow the version it holds.
  void take_cuts(SimState& state);

  ImplicitIntegrator m_integrator;
  StepStatus m_last;
  FemStageStats m_stats;
  std::uint64_t m_seen_version = 0;
  bool m_last_solve_converged = true;  ///< for the stats: the step before this one's solve
};

}  // namespace serosa::fem
