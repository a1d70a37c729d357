// The "take tool states" stage for scripted tools: each step, every tool whose device is
// script:FILE gets its pose at the end of the step from its tool path. Tools on other devices
// (rig, mouse) are fed by the haptics thread in a session and keep their last state headless.
#pragma once

#include <memory>
#include <string_view>
#include <vector>

#include "engine/scene/scene.h"
#include "engine/scene/tool_path.h"
#include "engine/stage.h"

namespace serosa {

class ScriptToolStage final : public Stage {
 public:
  /// Reads each distinct script file once. Throws InputError when a file is bad or does not
  /// mention the tool that uses it (naming the file and the tool).
  explicit ScriptToolStage(const Scene& scene);

  [[nodiscard]] std::string_view name() const noexcept override { return "tools"; }
  /// state.tools[i] = pose of tool i at ctx.time_s + ctx.dt_s (the end of the step).
  void step(const StepContext& ctx, SimState& state) override;

  /// Number of tools driven by a script.
  [[nodiscard]] std::size_t num_scripted() const noexcept { return m_bindings.size(); }
  /// Time of the last sample over every script, s: a headless run's natural length.
  [[nodiscard]] double end_time_s() const noexcept;

 private:
  struct Binding {
    std::size_t tool = 0;       // index into Scene::tools and SimState::tools
    std::size_t path = 0;       // index into m_paths
    std::size_t path_tool = 0;  // index of the tool inside that path
  };
  std::vector<ToolPath> m_paths;
  std::vector<Binding> m_bindings;
};

}  // namespace serosa
