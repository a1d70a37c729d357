// The composition root: maps the scene's effects to the stages that implement them and hands
// only those to the runner (shared/DESIGN.md "Effects: simulate only what the scene calls for").
// An effect the scene does not list is never constructed: no memory, no time.
#pragma once

#include <memory>
#include <vector>

#include "app/assemble_state.h"
#include "engine/runner.h"
#include "engine/scene.h"

namespace serosa::fem {
class FemStage;
}

namespace serosa::app {

class ScriptToolStage;

/// The runner with its stages, plus non-owning handles to the stages app needs to talk to.
struct Composition {
  std::unique_ptr<Runner> runner;
  std::vector<Effect> built;        ///< listed effects that have a stage in this build
  std::vector<Effect> unavailable;  ///< listed effects this build cannot simulate yet
  /// Listed effects that need no stage of their own in a headless run: "gravity" is a term of
  /// the FEM stage, "render" is drawn by the headless command when frames are asked for.
  std::vector<Effect> folded;
  ScriptToolStage* tools = nullptr;  ///< null when no tool is scripted
  fem::FemStage* fem = nullptr;      ///< null unless "fem" is listed
};

/// Builds the stages for `scene` in the pipeline order of DESIGN.md (tools -> contact -> FEM ->
/// cuts -> surface -> metrics -> publish -> record), only for listed effects.
[[nodiscard]] Composition compose(const Scene& scene, const AssembledScene& assembled);

}  // namespace serosa::app
