// Runner: takes one solver step at a time over the stages app composed, each in its place of the
// step, and times each. Runner::step (runner.cpp) is the whole step in order, read top to bottom:
//   tools -> haptics -> contact -> FEM -> cuts -> surface -> metrics -> record (-> snapshot)
// (docs/ARCHITECTURE.md "The step"). A place with no stage is an effect the scene does not list:
// it costs nothing. This is the synchronous core; the haptics and render threads attach to it
// through the hand-off primitives (seqlock.h, triple_buffer.h) and SimState::shared.
#pragma once

#include <chrono>
#include <cstdint>
#include <memory>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "engine/snapshot_sink.h"
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

/// One part of a snapshot: "state" (SimState without its blocks) or a block, by byte range.
struct SnapshotSection {
  std::string name;
  std::size_t offset = 0;
  std::size_t size = 0;
};

/// The snapshot version this build writes and reads.
[[nodiscard]] std::uint32_t snapshot_version() noexcept;
/// The version `snapshot` was written with; 0 when the bytes are not a snapshot.
[[nodiscard]] std::uint32_t snapshot_version(std::span<const std::uint8_t> snapshot) noexcept;
/// The parts of a snapshot (Runner::snapshot), checked; throws InputError naming `what`.
[[nodiscard]] std::vector<SnapshotSection> snapshot_sections(std::span<const std::uint8_t> snapshot,
                                                             const std::string& what);

struct StageTiming {
  std::string name;
  double total_s = 0.0;  ///< wall time spent in this stage over all steps, s
  std::uint64_t calls = 0;
  double last_s = 0.0;  ///< wall time of this stage in the last step, s
};

class Runner {
 public:
  explicit Runner(double dt_s);

  /// Puts `stage` in its place; stages of one place run in the order they were added.
  void add(Slot slot, std::unique_ptr<Stage> stage);
  /// Takes one solver step: every place in order, then advances time and step count.
  void step(SimState& state);
  /// Lets every stage build what the next step would (Stage::prepare): load time, not step time.
  /// Optional; the same bits either way.
  void prepare(SimState& state);
  /// Takes n steps.
  void run(SimState& state, std::uint64_t n);

  /// The whole state after the last step, SimState with its blocks, as bytes
  /// (engine/state_codec.h). Between steps only (no cut in flight).
  [[nodiscard]] std::vector<std::uint8_t> snapshot(const SimState& state) const;
  /// Restores a snapshot into `state`, then lets every stage adopt it (Stage::adopt: checks its
  /// block, rebuilds its caches) — stages built for the scene it was taken from, fresh or not.
  /// Throws InputError naming `what` when the bytes are damaged or do not fit these stages.
  void restore(std::span<const std::uint8_t> snapshot, SimState& state, const std::string& what);
  /// Hands a snapshot to `sink` every `every_steps` steps (0: never), at the end of the step:
  /// at the first step on or after each multiple of every_steps.
  void record_snapshots(SnapshotSink& sink, std::uint64_t every_steps);

  [[nodiscard]] double dt_s() const noexcept { return m_dt_s; }
  /// Each stage's timing, in the order the step runs them.
  [[nodiscard]] std::vector<StageTiming> timings() const;
  [[nodiscard]] std::size_t num_stages() const noexcept { return m_entries.size(); }
  /// Wall time of the stages named `name` in the last step, s (0 when there is none).
  [[nodiscard]] double last_stage_s(std::string_view name) const;

 private:
  struct Entry {
    Slot slot;
    std::unique_ptr<Stage> stage;
    StageTiming timing;
  };
  void record_snapshot_if_due(const SimState& state);
  /// Runs the stages in `slot`, timing each.
  void run_slot(Slot slot, const StepContext& ctx, SimState& state);

  double m_dt_s;
  std::vector<Entry> m_entries;  // ordered by slot, then by addition
  SnapshotSink* m_snapshot_sink = nullptr;
  std::uint64_t m_snapshot_every = 0;
  std::uint64_t m_next_snapshot = 0;  // step count at or after which the next one is written
};

}  // namespace serosa
