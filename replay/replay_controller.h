// ReplayController: the instructor's replay without a window (the core of `serosa replay` in a
// window; tests drive it directly): plays a .lapr recording forward at a speed, pauses, and seeks
// to any time. Forward seeks step on; backward seeks restart from a snapshot.
//
// Snapshots. The recording's whole-state snapshots (engine/state_codec.h), and those the
// controller takes every `snapshot_every_s` while it plays forward, hold SimState and every
// stage's own part (warm starts, factor schedule, strokes, grasps, metric sums): a backward seek
// restores the nearest one at or before the target into a fresh pipeline and re-simulates from
// there, O(snapshot interval), and every later state hash equals the recording's. from_start
// re-simulates from step 0 instead (O(t); the snapshot-free cross-check).
//
// Branching. After branch() each tool follows the recording until set_tool_input() first drives
// it (the mouse's instruments, the instructor's endoscope); from then on it keeps the input it was
// last given. So the hands the instructor did not take go on as the trainee moved them, and the
// branch recording writes whole-state snapshots at the recording's own cadence ([record]
// snapshot_every_s, at the first step on or after each multiple with no cut in flight, as
// Runner::record_snapshots does), after the parent's own up to the branch: `serosa replay
// BRANCH --from T` starts from the nearest one.
#pragma once

#include <cstdint>
#include <filesystem>
#include <map>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "engine/scene/scene.h"
#include "engine/sim_state.h"
#include "recording/recording_reader.h"
#include "recording/recording_writer.h"

namespace serosa::recording {
class RecordStage;
class ReplayInputStage;
class VerifyStage;
}  // namespace serosa::recording

namespace serosa::app {
struct Composition;
class Simulation;
struct SimulationHooks;
}  // namespace serosa::app

namespace serosa::replay {

using app::Composition;
using app::Simulation;
using app::SimulationHooks;

struct ReplayControllerOptions {
  double snapshot_every_s = 1.0;  ///< simulated time between snapshots, s (> 0)
  bool from_start = false;        ///< backward seeks re-simulate from step 0 (see above)
  double speed = 1.0;             ///< initial playback speed, x real time
};

class ReplayController {
 public:
  static constexpr double kMinSpeed = 1.0 / 16.0;
  static constexpr double kMaxSpeed = 16.0;

  /// Opens the recording and builds its scene from the header. Throws InputError when the file
  /// is not a usable recording (as run_replay does).
  explicit ReplayController(const std::filesystem::path& recording,
                            ReplayControllerOptions options = {});
  ~ReplayController();
  ReplayController(const ReplayController&) = delete;
  ReplayController& operator=(const ReplayController&) = delete;

  // ---- playback ----
  void set_paused(bool paused) { m_paused = paused; }
  [[nodiscard]] bool paused() const { return m_paused; }
  /// Clamped to [kMinSpeed, kMaxSpeed].
  void set_speed(double speed);
  [[nodiscard]] double speed() const { return m_speed; }
  /// Plays `wall_dt_s` of wall time at the current speed (nothing while paused or at the end):
  /// takes every step that became due. Returns the steps taken.
  std::uint64_t advance(double wall_dt_s);
  /// Takes one step (false at the end of the recording).
  bool step_forward();

  // ---- seeking ----
  /// To the state after `steps` recorded steps (clamped to the recording's length).
  void seek_step(std::uint64_t steps);
  /// To simulated time t, s: the state after round(t / dt) steps (clamped).
  void seek(double t_s);

  // ---- branching (take over from the replayed state) ----
  /// Branches here: from now on the tools follow set_tool_input() (the rig or the mouse) instead
  /// of the recording, and the run is recorded to `branch_file`: a complete recording from step 0
  /// (the parent's inputs and hashes up to here, then the new ones), so that `serosa replay
  /// branch_file --verify` re-simulates it; its header holds the parent's scene and keys plus
  /// "parent" (the parent's path) and "branch_step" (steps taken when it branched), and an event
  /// "branch" marks the step; the parent's snapshots up to the branch are copied into it and the
  /// branch's own follow at the recording's cadence (above). Playback may then go past the
  /// parent's end; seeks are refused.
  /// Throws std::logic_error unless exact() (the state must be the recorded one) or when already
  /// branched; std::runtime_error when the file cannot be written.
  void branch(const std::filesystem::path& branch_file);
  /// Sets tool `i`'s input (scene order) for the next steps of a branch: from now on the
  /// recording no longer drives it. Throws std::logic_error when not branched, std::out_of_range
  /// for a bad index.
  void set_tool_input(std::size_t i, const ToolState& input);
  /// Whether tool `i` still follows the recording (before a branch: every tool; in a branch: those
  /// set_tool_input() never drove; past the recording's end they hold its last input).
  [[nodiscard]] bool recording_drives(std::size_t i) const;
  /// Closes the branch's recording (end record); playback stops. Idempotent.
  void end_branch();
  [[nodiscard]] bool branched() const { return m_branch_writer != nullptr; }
  [[nodiscard]] std::optional<std::uint64_t> branch_step() const { return m_branch_step; }

  // ---- where we are ----
  [[nodiscard]] std::uint64_t steps_taken() const;  ///< = state().step
  [[nodiscard]] std::uint64_t num_steps() const { return m_rec.inputs.size(); }
  [[nodiscard]] double dt_s() const { return m_scene.settings.dt_s; }
  [[nodiscard]] double time_s() const;
  [[nodiscard]] double duration_s() const { return static_cast<double>(num_steps()) * dt_s(); }
  /// At the recording's end (never while a branch records; always once it is closed).
  [[nodiscard]] bool at_end() const;
  /// True while the state follows the recording bit for bit (until a branch).
  [[nodiscard]] bool exact() const { return m_exact; }
  /// The hash of the state as the recording hashes it (after the stages of the last step, before
  /// the step counter advanced); nullopt before the first step.
  [[nodiscard]] std::optional<std::uint64_t> last_step_hash() const;
  /// Recorded hashes compared so far on this pipeline, and the first step whose hash differed.
  [[nodiscard]] std::uint64_t hashes_checked() const;
  [[nodiscard]] std::optional<std::uint64_t> diverged_at() const;
  [[nodiscard]] std::size_t num_snapshots() const { return m_snapshots.size(); }
  /// Full restarts so far (the first build included): tests check which seeks restart.
  [[nodiscard]] std::uint64_t restarts() const { return m_restarts; }

  [[nodiscard]] const SimState& state() const;
  [[nodiscard]] const Scene& scene() const { return m_scene; }
  [[nodiscard]] const recording::Recording& recording() const { return m_rec; }
  [[nodiscard]] const Composition& composition() const;
  [[nodiscard]] std::map<int, std::string> group_names() const;

 private:
  /// The stages the controller talks to, in the driver's pipeline.
  struct Stages {
    recording::ReplayInputStage* input = nullptr;
    recording::RecordStage* record = nullptr;  // records only once a branch attaches its writer
    recording::VerifyStage* hash = nullptr;
  };
  struct Snapshot {
    std::vector<std::uint8_t> bytes;    // Runner::snapshot
    std::optional<std::uint64_t> hash;  // last_step_hash() there, when known
  };
  void restart(const Snapshot* from);
  /// The recorded inputs, the record stage and the hash check, composed into each pipeline the
  /// driver builds (into m_next: m_stages once the pipeline is in use).
  SimulationHooks hooks();

  recording::Recording m_rec;
  Scene m_scene;
  ReplayControllerOptions m_options;
  std::unique_ptr<Simulation> m_sim;              // the headless driver, fed the recorded inputs
  Stages m_stages;                                // of the pipeline in use
  Stages m_next;                                  // of the pipeline the driver built last
  std::map<std::uint64_t, Snapshot> m_snapshots;  // steps taken -> snapshot
  std::uint64_t m_snapshot_every = 1;             // steps
  double m_speed = 1.0;
  double m_due = 0.0;  // simulated time owed to playback, s
  bool m_paused = false;
  bool m_exact = true;
  std::uint64_t m_restarts = 0;
  std::filesystem::path m_path;
  void copy_prefix(std::uint64_t k);     // the parent's records before step k, to the branch
  void record_branch_snapshot_if_due();  // after a branch step
  void feed_recorded_inputs();           // before a branch step: the tools the recording drives

  std::unique_ptr<recording::RecordingWriter> m_branch_writer;
  std::optional<std::uint64_t> m_branch_step;
  bool m_branch_closed = false;
  std::vector<bool> m_driven;                 // (tools) set_tool_input() drove it in the branch
  std::uint64_t m_branch_snapshot_every = 0;  // steps ([record] snapshot_every_s; 0: none)
  std::uint64_t m_branch_next_snapshot = 0;   // steps at or after which the next is written
};

}  // namespace serosa::replay
