// The "record" stage (last in the pipeline): hands the recording writer the tool inputs the
// solver consumed this step and, every `hash_every` steps, the state hash; and its mirror for
// replay, which feeds recorded inputs back ("tools" position) and checks the hashes (last).
//
// Both hash at the same point: after every other stage of step k, before the runner advances
// the step counter (so the hash covers time and step k as they were during the step).
#pragma once

#include <cstdint>
#include <map>
#include <optional>
#include <string_view>
#include <vector>

#include "engine/stage.h"
#include "engine/tool_state.h"
#include "recording/recording_writer.h"

namespace serosa::recording {

/// Whether step k's hash is recorded: every hash_every-th step (k + 1 a multiple of it).
[[nodiscard]] inline bool hashed_step(std::uint64_t k, std::int64_t hash_every) {
  return hash_every > 0 && (k + 1) % static_cast<std::uint64_t>(hash_every) == 0;
}

class RecordStage final : public Stage {
 public:
  /// writer: where to record; null records nothing until attach() (a replay that may branch).
  RecordStage(recording::RecordingWriter* writer, std::int64_t hash_every)
      : m_writer(writer), m_hash_every(hash_every) {}
  [[nodiscard]] std::string_view name() const noexcept override { return "record"; }
  void step(const StepContext& ctx, SimState& state) override;
  /// Records the following steps to `writer` (null: stops recording).
  void attach(recording::RecordingWriter* writer) noexcept { m_writer = writer; }

 private:
  recording::RecordingWriter* m_writer;
  std::int64_t m_hash_every;
};

/// Replay's "tools" stage: state.tools = the inputs recorded for this step, or, once live, the
/// inputs set by hand (a branch taking over from the recording).
class ReplayInputStage final : public Stage {
 public:
  explicit ReplayInputStage(const std::vector<std::vector<ToolState>>& inputs) : m_inputs(inputs) {}
  [[nodiscard]] std::string_view name() const noexcept override { return "tools"; }
  /// Throws std::out_of_range past the recorded steps (the replay loop stops before).
  void step(const StepContext& ctx, SimState& state) override;
  /// From now on the tools keep `tools` (scene order) until set_live() changes one.
  void go_live(std::vector<ToolState> tools) { m_live = std::move(tools); }
  /// Sets tool i's live input. Throws std::logic_error before go_live(), std::out_of_range for a
  /// bad index.
  void set_live(std::size_t i, const ToolState& input);

 private:
  const std::vector<std::vector<ToolState>>& m_inputs;
  std::optional<std::vector<ToolState>> m_live;
};

/// Replay's check: compares the state hash with the recorded one at every recorded step.
class VerifyStage final : public Stage {
 public:
  /// every_step: also hash the steps the recording did not (last_hash() after every step).
  explicit VerifyStage(const std::map<std::uint64_t, std::uint64_t>& hashes,
                       bool every_step = false)
      : m_hashes(hashes), m_every_step(every_step) {}
  [[nodiscard]] std::string_view name() const noexcept override { return "verify"; }
  void step(const StepContext& ctx, SimState& state) override;
  /// The hash after the last step hashed (every step with every_step); nullopt before any.
  [[nodiscard]] std::optional<std::uint64_t> last_hash() const noexcept { return m_last; }
  /// Starts from a restored state whose last hash was `h`.
  void set_last_hash(std::optional<std::uint64_t> h) noexcept { m_last = h; }

  struct Divergence {
    std::uint64_t step = 0;
    std::uint64_t recorded = 0;
    std::uint64_t replayed = 0;
  };
  [[nodiscard]] const std::optional<Divergence>& divergence() const noexcept {
    return m_divergence;
  }
  [[nodiscard]] std::uint64_t checked() const noexcept { return m_checked; }

 private:
  const std::map<std::uint64_t, std::uint64_t>& m_hashes;
  bool m_every_step;
  std::optional<std::uint64_t> m_last;
  std::optional<Divergence> m_divergence;  // the first one
  std::uint64_t m_checked = 0;
};

}  // namespace serosa::recording
