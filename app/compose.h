// The composition root: maps the scene's effects to the stages that implement them and hands
// only those to the runner (docs/ARCHITECTURE.md "Effects").
// An effect the scene does not list is never constructed: no memory, no time.
#pragma once

#include <filesystem>
#include <memory>
#include <optional>
#include <vector>

#include "app/assemble_state.h"
#include "contact/clip_stage.h"
#include "contact/tool_contact_stage.h"
#include "cutting/cutting_stage.h"
#include "engine/live_pose_stage.h"
#include "engine/runner.h"
#include "engine/scene/scene.h"
#include "engine/script_tool_stage.h"
#include "engine/tissue_stress.h"
#include "fem/fem_config.h"
#include "fem/fem_stage.h"
#include "haptics/haptics_stage.h"
#include "metrics/metrics_stage.h"
#include "recording/record_stage.h"
#include "recording/recording_writer.h"
#include "surface/surface_stage.h"

namespace serosa::app {

// The stages, each in the folder of its domain; the composition root names them all.
using contact::ClipStage;
using contact::ToolContactStage;
using cutting::CuttingStage;
using cutting::CuttingStageOptions;
using cutting::CuttingStageStats;
using cutting::kCheckEveryCutByDefault;
using haptics::HapticsStage;
using haptics::HapticsStageOptions;
using haptics::mouse_handle;
using haptics::MouseHandle;
using haptics::rig_trocar;
using metrics::distance_to_polyline;
using metrics::MetricsStage;
using recording::hashed_step;
using recording::RecordStage;
using recording::ReplayInputStage;
using recording::VerifyStage;
using surface::SurfaceStage;

/// How to compose, beyond what the scene says.
struct ComposeOptions {
  /// Replaces the scripted "tools" stage as the source of tool inputs (replay feeds recorded
  /// inputs this way). Null: tools driven by a script get a ScriptToolStage.
  std::unique_ptr<Stage> tool_input;
  /// Check every cut's invariants (cutting/validate.h); costly, for tests (always on in debug
  /// builds: kCheckEveryCutByDefault).
  bool validate_cuts = false;
  /// The haptic loop asks for SCHED_FIFO and runs its gap monitor (the trainee session).
  bool realtime_haptics = false;
  /// (tools, or empty) How mouse-driven tools rest at the start (HapticsStageOptions).
  std::vector<std::optional<ToolState>> mouse_rest_pose;
  /// Tools another thread poses (the session's endoscope in the trainee's hands): a
  /// LivePoseStage in the tools slot, after the scripts.
  std::vector<LivePoseStage::Source> live_poses;
};

/// The runner with its stages, plus non-owning handles to the stages app needs to talk to.
struct Composition {
  std::unique_ptr<Runner> runner;
  std::vector<Effect> built;        ///< listed effects that have a stage in this build
  std::vector<Effect> unavailable;  ///< listed effects this build cannot simulate yet
  /// Listed effects the command handles, with no stage of compose's: "render" is drawn when
  /// frames or a window are asked for, "record" is recorded when a file is given (the command
  /// then adds the record stage and moves it to `built`).
  std::vector<Effect> folded;
  ScriptToolStage* tools = nullptr;     ///< null when no tool is scripted
  HapticsStage* haptics = nullptr;      ///< null unless "haptics" is listed (not in replay)
  fem::FemStage* fem = nullptr;         ///< null unless "fem" is listed
  CuttingStage* cutting = nullptr;      ///< null unless "cutting" is listed
  SurfaceStage* surface = nullptr;      ///< null unless "surface" is listed
  ToolContactStage* contact = nullptr;  ///< null unless "contact" is listed
  ClipStage* clips = nullptr;           ///< null unless "clips" is listed
  MetricsStage* metrics = nullptr;      ///< built with "fem" (stress needs it)
  Stage* tool_input = nullptr;          ///< ComposeOptions::tool_input once handed to the runner
};

/// The command added the record stage: "record" moves from `folded` to `built`.
void mark_recording(Composition& c);

/// Records the run to `path` (the command line's, else the scene's [record] path): the record
/// stage last in the step, and a whole-state snapshot every [record] snapshot_every_s. Without
/// either path a scene listing "record" is told (info) it is not recorded, and null is returned.
/// `run` names the run in that message ("run", "session"). Throws InputError naming the path
/// when it cannot be written.
[[nodiscard]] std::unique_ptr<recording::RecordingWriter> record_run(
    Composition& c, const Scene& scene, const std::optional<std::filesystem::path>& path,
    const recording::Header& header, const char* run);

/// The scene's solver kind as fem's.
[[nodiscard]] fem::SolverKind to_fem(SolverKind k);
/// The FEM model of `scene`: a material per group, the solver settings, gravity when listed.
[[nodiscard]] fem::FemConfig fem_config(const Scene& scene, const AssembledScene& assembled);
/// The Lamé parameters per group (stress metrics, grasp forces).
[[nodiscard]] LameTable lame_table(const Scene& scene, const AssembledScene& assembled);

/// Builds the stages for `scene` in the pipeline order (tools -> contact -> FEM ->
/// cuts -> surface -> metrics -> publish -> record), only for listed effects.
[[nodiscard]] Composition compose(const Scene& scene, const AssembledScene& assembled,
                                  ComposeOptions options = {});

}  // namespace serosa::app
