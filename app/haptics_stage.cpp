#include "app/haptics_stage.h"

#include <sstream>

#include "engine/input_error.h"
#include "engine/sim_state.h"
#include "engine/tool_path.h"
#include "haptics/haptic_loop.h"
#include "haptics/script_device.h"

namespace serosa::app {

HapticsStage::HapticsStage(const Scene& scene) {
  std::size_t handle = 0;
  std::optional<std::filesystem::path> script;
  for (std::size_t i = 0; i < scene.tools.size() && handle < haptics::kHandles; ++i) {
    const Tool& t = scene.tools[i];
    if (t.kind == ToolKind::kEndoscope || t.device.kind != DeviceKind::kScript) continue;
    if (script && *script != t.device.script)
      throw InputError(t.device.script.string(), 0,
                       "the haptic handles' tools must share one script file", script->string());
    script = t.device.script;
    m_tool[handle++] = i;
  }
  if (!script)
    throw InputError(scene.file.string(), 0, "\"haptics\" needs a scripted instrument",
                     "a grasper or scissors with device = \"script:FILE\"");
  ToolPath path = read_tool_path(*script);
  std::array<std::optional<std::size_t>, haptics::kHandles> of_handle{};
  std::array<haptics::Trocar, haptics::kHandles> trocars{};
  for (std::size_t h = 0; h < haptics::kHandles; ++h) {
    if (!m_tool[h]) continue;
    const Tool& t = scene.tools[*m_tool[h]];
    of_handle[h] = path.index_of(t.name);
    if (!of_handle[h])
      throw InputError(script->string(), 0, "no rows for tool '" + t.name + "'",
                       "rows whose tool column is '" + t.name + "'");
    const ToolState first = sample(path, *of_handle[h], 0.0);
    const Vec3 tip(first.tip_m[0], first.tip_m[1], first.tip_m[2]);
    trocars[h].pivot_m = t.trocar_m.value_or(tip);
    const Vec3 axis = tip - trocars[h].pivot_m;
    if (axis.norm() > 1e-9)
      trocars[h].rotation = Quat::FromTwoVectors(Vec3::UnitZ(), axis.normalized());
  }
  m_device = std::make_unique<haptics::ScriptDevice>(std::move(path), of_handle, trocars);
  haptics::HapticLoopConfig c;
  c.trocars = trocars;
  c.realtime = false;     // headless runs share the machine (CI): no SCHED_FIFO
  c.gap_monitor = false;  // nor a second polling thread
  m_loop = std::make_unique<haptics::HapticLoop>(*m_device, m_model, c);
}

HapticsStage::~HapticsStage() { stop(); }

void HapticsStage::stop() {
  if (m_loop && m_loop->running()) m_loop->stop();
}

void HapticsStage::step(const StepContext& ctx, SimState& state) {
  // Solver -> loop: the model of the state as it enters this step.
  haptics::ContactModel model;
  model.step = ctx.step + 1;  // 0 means "no model yet"
  model.time_s = ctx.time_s;
  for (std::size_t h = 0; h < haptics::kHandles; ++h)
    if (m_tool[h] && *m_tool[h] < state.tools.size())
      model.tools[h].sim_tip_m = state.tools[*m_tool[h]].tip_m;
  m_model.store(model);
  if (!m_started) {
    m_loop->start();
    m_started = true;
  }
  // Loop -> solver: the newest state of each handle (kept from the script until the first tick).
  for (std::size_t h = 0; h < haptics::kHandles; ++h) {
    if (!m_tool[h] || *m_tool[h] >= state.tools.size()) continue;
    const ToolState t = m_loop->tool_state(h).load();
    if (t.tick > 0) state.tools[*m_tool[h]] = t;
  }
}

nlohmann::json HapticsStage::telemetry_json() {
  stop();
  std::ostringstream os;
  m_loop->telemetry().write_json(os);
  return nlohmann::json::parse(os.str());
}

}  // namespace serosa::app
