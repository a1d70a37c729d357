// Stage: one step of the solver pipeline (take tool states -> contact -> FEM -> cuts -> surface
// update -> metrics -> publish -> record; docs/ARCHITECTURE.md "The step").
// app builds one stage per effect the scene lists and hands them, in that order, to the Runner.
#pragma once

#include <cstdint>
#include <string_view>

namespace serosa {

struct SimState;

/// What every stage knows about the step it is part of.
struct StepContext {
  std::uint64_t step = 0;  ///< index of the step being taken (0-based)
  double time_s = 0.0;     ///< simulated time at the start of the step, s
  double dt_s = 0.0;       ///< step length, s
};

/// A stage holds its own read-only model (given at construction) and its private caches; each
/// step it reads and writes the shared SimState. Stages never call each other.
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
};

}  // namespace serosa
