// Runner: takes one solver step at a time over the stages app composed, each in its place of the
// step, and times each. Runner::step (runner.cpp) is the whole step in order, read top to bottom:
//   tools -> haptics -> contact -> FEM -> cuts -> surface -> metrics -> record
// (docs/ARCHITECTURE.md "The step"). A place with no stage is an effect the scene does not list:
// it costs nothing. This is the synchronous core; the haptics and render threads attach to it
// through the hand-off primitives (seqlock.h, triple_buffer.h) and SimState::handoff.
#pragma once

#include <chrono>
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "engine/stage.h"

namespace serosa {

struct SimState;

/// The places of a solver step, in the order Runner::step runs them.
enum class Slot : std::uint8_t {
  tools,    ///< take the tool states: scripted paths, replayed inputs
  haptics,  ///< the haptic loop's handles override their tools; it gets the contact model
  contact,  ///< tools touch and grasp the tissue: forces and held nodes for FEM
  fem,      ///< one implicit corotational step (gravity is one of its terms)
  cutting,  ///< closing blades cut; the cuts are handed on
  surface,  ///< the boundary follows the cuts
  metrics,  ///< what the trainee is scored on
  record,   ///< what the step consumed, and state hashes, to a recording (or checked: verify)
};

struct StageTiming {
  std::string name;
  double total_s = 0.0;  ///< wall time spent in this stage over all steps, s
  std::uint64_t calls = 0;
};

class Runner {
 public:
  explicit Runner(double dt_s);

  /// Puts `stage` in its place; stages of one place run in the order they were added.
  void add(Slot slot, std::unique_ptr<Stage> stage);
  /// Takes one solver step: every place in order, then advances time and step count.
  void step(SimState& state);
  /// Takes n steps.
  void run(SimState& state, std::uint64_t n);

  [[nodiscard]] double dt_s() const noexcept { return m_dt_s; }
  /// Each stage's timing, in the order the step runs them.
  [[nodiscard]] std::vector<StageTiming> timings() const;
  [[nodiscard]] std::size_t num_stages() const noexcept { return m_entries.size(); }

 private:
  struct Entry {
    Slot slot;
    std::unique_ptr<Stage> stage;
    StageTiming timing;
  };
  /// Runs the stages in `slot`, timing each.
  void run_slot(Slot slot, const StepContext& ctx, SimState& state);

  double m_dt_s;
  std::vector<Entry> m_entries;  // ordered by slot, then by addition
};

}  // namespace serosa
