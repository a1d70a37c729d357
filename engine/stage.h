// Stage: one step of the solver pipeline (take tool states -> contact -> FEM -> cuts -> surface
// update -> metrics -> publish -> record; docs/ARCHITECTURE.md "The step").
// app builds one stage per effect the scene lists and hands them, in that order, to the Runner.
#pragma once

#include <cstdint>
#include <stdexcept>
#include <string_view>

namespace serosa {

struct SimState;
class StateWriter;
class StateReader;

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
/// What a stage keeps from one step to the next that SimState does not hold and that cannot be
/// derived from it (FEM's warm starts and factor schedule, a stroke in progress, grasp holds,
/// metric sums) is its block of the whole state: save() writes it and restore() reads it back
/// into a stage freshly built for the same scene, so that a restored run continues bit for bit
/// (engine/state_codec.h, Runner::snapshot). Caches derived from SimState are not saved: a
/// restored stage rebuilds them.
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
  /// Writes this stage's block of the whole state (nothing: a stage that keeps none).
  virtual void save(StateWriter& /*out*/) const {}
  /// Reads the block save() wrote, after `state` (restored; a stage may rebuild what it derives
  /// into it, as FEM its masses) and before the next step. Throws
  /// InputError (through the reader) when the block does not fit this stage.
  virtual void restore(StateReader& /*in*/, SimState& /*state*/) {}
  /// The whole state was replaced (a snapshot restored): checks that this stage's block of it
  /// (SimState::blocks) fits the scene and the mesh, throwing BlockMismatch when it does not, and
  /// drops or rebuilds what the stage derives from the state (trees, tables, what it publishes in
  /// SimState::shared), so that the next step gives the bits the uninterrupted run would.
  virtual void adopt(SimState& /*state*/) {}
};

}  // namespace serosa
