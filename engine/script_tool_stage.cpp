#include "engine/script_tool_stage.h"

#include <algorithm>

#include "engine/input_error.h"
#include "engine/sim_state.h"

namespace serosa {

ScriptToolStage::ScriptToolStage(const Scene& scene) {
  std::vector<std::filesystem::path> files;
  for (std::size_t i = 0; i < scene.tools.size(); ++i) {
    const Tool& tool = scene.tools[i];
    if (tool.device.kind != DeviceKind::kScript) continue;
    auto it = std::find(files.begin(), files.end(), tool.device.script);
    if (it == files.end()) {
      m_paths.push_back(read_tool_path(tool.device.script));
      files.push_back(tool.device.script);
      it = files.end() - 1;
    }
    const auto p = static_cast<std::size_t>(it - files.begin());
    const auto index = m_paths[p].index_of(tool.name);
    if (!index)
      throw InputError(tool.device.script.string(), 0,
                       "no rows for tool '" + tool.name + "' of scene " + scene.file.string(),
                       "rows whose tool column is '" + tool.name + "'");
    m_bindings.push_back({i, p, *index});
  }
}

void ScriptToolStage::step(const StepContext& ctx, SimState& state) {
  for (const Binding& b : m_bindings)
    state.tools[b.tool] = sample(m_paths[b.path], b.path_tool, ctx.time_s + ctx.dt_s);
}

double ScriptToolStage::end_time_s() const noexcept {
  double t = 0.0;
  for (const ToolPath& p : m_paths) t = std::max(t, p.end_time_s());
  return t;
}

}  // namespace serosa
