// Simulation: one scene loaded, assembled, composed and prepared, stepped one solver step at a
// time and reported on. It is the one driver of every run: `serosa headless` (run_headless:
// construct, step, finish), the trainee session's solver thread, the replay headless and in a
// window (their additions through SimulationHooks), `serosa bench`, and the object the Python
// module wraps (python/serosa_module.cpp, docs/python.md): a program steps the same stages, in
// the same order, to the same bits as the command.
// Tools whose device is "python" take the pose set_tool gives them at the next step boundary
// (a LivePoseStage in the tools place, so a recording records what the solver consumed).
#pragma once

#include <chrono>
#include <cstdint>
#include <functional>
#include <memory>
#include <optional>
#include <span>
#include <vector>

#include <nlohmann/json.hpp>

#include "app/assemble_state.h"
#include "app/compose.h"
#include "app/headless_options.h"
#include "app/output_paths.h"
#include "app/run_report.h"
#include "app/run_series.h"
#include "app/run_warnings.h"
#include "cutting/convex_polygon.h"
#include "engine/scene/scene.h"
#include "engine/seqlock.h"

namespace serosa::app {

class FramePictures;

/// What a caller adds to a run: a replay drives the tools by the recorded inputs and checks
/// hashes after the record slot, a trainee session puts tools in the trainee's hands and keeps
/// the pace itself. The functions are called at load and again at each restore or reset, which
/// compose the stages anew, so that what they add always belongs to the pipeline in use.
struct SimulationHooks {
  /// Replaces the scripted tools stage as the source of tool inputs (ComposeOptions::tool_input).
  std::function<std::unique_ptr<Stage>()> tool_input;
  /// Adds stages to the composed runner.
  std::function<void(Runner&)> extend;
  /// Sets what else the composition needs (a trainee session: the mouse's rest poses, the
  /// endoscope in the trainee's hands, real-time haptics).
  std::function<void(ComposeOptions&)> compose;
  /// The caller keeps the wall-clock pace (the session's solver loop): step() never waits for
  /// a rig's hands.
  bool caller_paces = false;
  /// Names the run in the message that it is not recorded ("run", "session").
  const char* run_name = "run";
  /// Prints nothing of the scene's own (its empty selections, its effects this build lacks):
  /// the run that was recorded said it.
  bool quiet = false;
};

class Simulation {
 public:
  /// Checks every output `options` names, loads the scene with its overrides and tool path
  /// (InputError naming the file, key and line), builds the listed effects' stages, opens the
  /// recording and prepares the first step (load time).
  explicit Simulation(const HeadlessOptions& options);
  /// The same with `scene` already loaded (a benchmark sets its solver fields directly); the
  /// options' scene and overrides are not read.
  Simulation(Scene scene, const HeadlessOptions& options, SimulationHooks hooks = {});
  ~Simulation();
  Simulation(const Simulation&) = delete;
  Simulation& operator=(const Simulation&) = delete;

  /// One solver step: every stage in its place, timed; then the series, VTU and picture due.
  void step();
  /// The steps the options asked for (--steps, --seconds, else the scene's headless.steps).
  [[nodiscard]] std::int64_t planned_steps() const noexcept { return m_planned; }

  /// The pictures drawn so far: "frames" (their files), "frames_camera", "frames_flat",
  /// "frames_blood" (docs/headless-report.md); empty without options.frames.
  [[nodiscard]] nlohmann::json picture_blocks() const;
  /// The run's report so far (docs/headless-report.md), without the blocks only the end writes
  /// ("haptics", "recording", "export_final", "series", "vtu_series").
  [[nodiscard]] nlohmann::json report() const;
  /// Ends the run: stops the haptic loop, closes the recording and the series, writes the final
  /// mesh and the report file the options name; returns the whole report. Once. `interrupted`:
  /// the run stopped before its planned steps (the report says so).
  nlohmann::json finish(bool interrupted = false);
  /// Stops the haptic loop (motors off), then closes the recording; returns their blocks of the
  /// report ("haptics", "recording"), those the run has. Once (finish() calls it; later calls
  /// return nothing).
  nlohmann::json stop();
  /// Room for `steps` steps' timings: an open-ended run (a session) allocates none while it
  /// steps, up to that many.
  void reserve(std::int64_t steps);

  /// Poses tool `tool` (index into Scene::tools) for the next step. Throws std::invalid_argument
  /// naming it unless its device is "python".
  void set_tool(std::size_t tool, const ToolState& pose);
  /// The pose set_tool last gave `tool`, or nullopt when none was (or its device is not python).
  [[nodiscard]] std::optional<ToolState> pose_set(std::size_t tool) const;
  /// Cuts `polygon` (convex, planar, world coordinates, m) through the cutting stage in one
  /// step (CuttingStage::queue_cut); returns what it did. Throws std::invalid_argument when the
  /// scene does not list "cutting".
  cutting::StrokeReport cut(const cutting::ConvexPolygon& polygon);
  /// The whole state (Runner::snapshot). Throws std::logic_error while a cut is in flight (the
  /// step that cut: take one more step).
  [[nodiscard]] std::vector<std::uint8_t> snapshot() const;
  /// Rebuilds the stages from the scene and restores `bytes` into them (Runner::restore): the
  /// run goes on bit for bit as from where the snapshot was taken. InputError naming `what` on
  /// damaged bytes. Not while recording (the recording would no longer be one run).
  void restore(std::span<const std::uint8_t> bytes, const std::string& what);
  /// Back to the scene's initial state in freshly composed stages, as at load. Not while
  /// recording.
  void reset();

  [[nodiscard]] const Scene& scene() const noexcept { return m_scene; }
  [[nodiscard]] const SimState& state() const noexcept { return m_pipe->assembled.state; }
  [[nodiscard]] const AssembledScene& assembled() const noexcept { return m_pipe->assembled; }
  [[nodiscard]] const Composition& composition() const noexcept { return m_pipe->comp; }
  /// (steps) Wall time of each step this run took, ms (Runner::step, every stage).
  [[nodiscard]] const std::vector<double>& step_ms() const noexcept { return m_step_ms; }

 private:
  /// The state and the stages stepping it, together: stages may keep references into the state
  /// they were composed for, so a restore builds a new pair and swaps it in whole.
  struct Pipeline {
    AssembledScene assembled;
    Composition comp;
  };
  /// The initial state and stages freshly composed for it (at load and at restore).
  [[nodiscard]] std::unique_ptr<Pipeline> build() const;
  /// The report's blocks known before the first step.
  void start_report();
  /// The picture taker and the steps it draws at (options.frames, options.frame_count).
  void plan_pictures(const std::filesystem::path& folder);
  /// Draws the pictures due at `step` (options.frames).
  void take_picture_if_due(std::int64_t step);
  /// The blocks after the steps: timing, meshes, cuts, metrics, then add_stage_blocks.
  void add_run_blocks(nlohmann::json& report) const;
  /// Contact, clips, surface, FEM and the warnings.
  void add_stage_blocks(nlohmann::json& report) const;

  HeadlessOptions m_options;
  SimulationHooks m_hooks;
  std::optional<MeshOutputFormat> m_final_format;
  Scene m_scene;
  std::int64_t m_planned = 0;
  AssembledScene m_initial;  // the assembled state before the first step (restore rebuilds it)
  std::unique_ptr<Pipeline> m_pipe;
  std::unique_ptr<recording::RecordingWriter> m_writer;
  /// (tools) The pose channel of each tool a Python program drives; null for the others.
  std::vector<std::unique_ptr<Seqlock<ToolState>>> m_python_poses;
  std::uint64_t m_pose_tick = 0;  // set_tool's sample count (a channel with tick 0 is unset)

  nlohmann::json m_report;  // the blocks known at load and the pictures taken
  std::vector<RunWarning> m_warnings;
  std::unique_ptr<FramePictures> m_pictures;
  std::vector<std::int64_t> m_picture_steps;
  double m_render_s = 0.0;  // wall time drawing pictures, s
  std::int64_t m_rendered = 0;
  std::optional<StepSeries> m_series;
  std::optional<VtuSeries> m_vtu;
  double m_prepare_ms = 0.0;                                     // Runner::prepare, ms
  std::chrono::steady_clock::time_point m_wall0;                 // construction
  std::optional<std::chrono::steady_clock::time_point> m_step0;  // the first step's start
  std::vector<double> m_step_ms;                                 // (steps) wall time per step, ms
  std::vector<StepDetail> m_details;                             // (steps) where it went
  bool m_paced = false;  // a rig's hand moves in wall-clock time: no faster than real time
  bool m_finished = false;
  bool m_stopped = false;  // stop(): the haptic loop stopped, the recording closed
};

}  // namespace serosa::app
