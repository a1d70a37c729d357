// Stage: one step of the solver pipeline (take tool states -> contact -> FEM -> cuts -> surface
// update -> metrics -> publish -> record; docs/ARCHITECTURE.md "The step").
// app builds one stage per effect the scene lists and hands them, in that order, to the Runner.
#pragma once

#include <cstdint>
#include <stdexcept>
#include <string_view>

namespace serosa {

struct SimState;

/// A restored block that does not fit the stage's scene or the restored mesh (Stage::adopt); the
/// runner names the snapshot and the block and throws InputError.
class BlockMismatch : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

/// What every stage knows about the step it is part of.
struct StepContext {
  std::uint64_t step = 0;  ///< index of the step being taken (0-based)
  double time_s = 0.0;     ///< simulated time at the start of the step, s
  double dt_s = 0.0;       ///< step length, s
};

/// A stage holds its own read-only model (given at construction) and its private caches; each
/// step it reads and writes the shared SimState. Stages never call each other.
///
/// What a stage carries from one step to the next that the mesh and the tools do not hold (FEM's
/// warm starts and factor schedule, a stroke in progress, grasp holds, metric sums) is its block
/// of the state, SimState::blocks (engine/state_blocks.h): the stage keeps nothing a restored
/// state could not give back, and a snapshot is SimState alone (engine/state_codec.h).
class Stage {
 public:
  virtual ~Stage() = default;
  Stage() = default;
  Stage(const Stage&) = delete;
  Stage& operator=(const Stage&) = delete;

  /// Short name used in reports and timings ("fem", "cutting", ...).
  [[nodiscard]] virtual std::string_view name() const noexcept = 0;
  /// Advances this stage's part of the state by one step. Must not throw on bad physics: it
  /// counts warnings in its status instead. Throws only on programming errors.
  virtual void step(const StepContext& ctx, SimState& state) = 0;
  /// Builds, before the first step and outside its time, what that step would build itself (FEM's
  /// matrix structure and first factor). Optional: a run gives the same bits without it.
  virtual void prepare(const StepContext& /*ctx*/, SimState& /*state*/) {}
  /// The whole state was replaced (a snapshot restored): checks that this stage's block of it
  /// (SimState::blocks) fits the scene and the mesh, throwing BlockMismatch when it does not, and
  /// drops or rebuilds what the stage derives from the state (trees, tables, what it publishes in
  /// SimState::shared), so that the next step gives the bits the uninterrupted run would.
  virtual void adopt(SimState& /*state*/) {}
};

}  // namespace serosa
