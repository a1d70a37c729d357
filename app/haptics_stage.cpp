#include "app/haptics_stage.h"

#include <sstream>

#include "app/tool_contact_stage.h"
#include "engine/input_error.h"
#include "engine/sim_state.h"
#include "engine/tool_path.h"
#include "haptics/haptic_loop.h"
#include "haptics/script_device.h"

namespace serosa::app {

MouseHandle mouse_handle(const Tool& tool, std::size_t handle, const Vec3& aim_m) {
  MouseHandle m;
  const Vec3 side = handle == 0 ? Vec3(-0.05, 0.0, 0.0) : Vec3(0.05, 0.0, 0.0);
  m.trocar.pivot_m = tool.trocar_m.value_or(Vec3(aim_m + Vec3(0.0, 0.12, 0.0) + side));
  Vec3 axis = aim_m - m.trocar.pivot_m;
  if (axis.norm() < 1e-6) axis = Vec3(0.0, -1.0, 0.0);
  m.trocar.rotation = Quat::FromTwoVectors(Vec3::UnitZ(), axis.normalized());
  m.rest.insertion_m = 0.5 * axis.norm();
  return m;
}

HapticsStage::HapticsStage(const Scene& scene, const HapticsStageOptions& options)
    : m_contact(options.contact) {
  std::size_t handle = 0;
  std::optional<DeviceKind> kind;
  std::optional<std::filesystem::path> script;
  for (std::size_t i = 0; i < scene.tools.size() && handle < haptics::kHandles; ++i) {
    const Tool& t = scene.tools[i];
    if (t.kind == ToolKind::kEndoscope) continue;
    if (t.device.kind != DeviceKind::kScript && t.device.kind != DeviceKind::kMouse) continue;
    if (kind && *kind != t.device.kind)
      throw InputError(scene.file.string(), 0,
                       "the haptic handles' tools must share one device kind: tool '" + t.name +
                           "' is driven by " + std::string(device_kind_name(t.device.kind)),
                       std::string(device_kind_name(*kind)));
    kind = t.device.kind;
    if (t.device.kind == DeviceKind::kScript) {
      if (script && *script != t.device.script)
        throw InputError(t.device.script.string(), 0,
                         "the haptic handles' tools must share one script file", script->string());
      script = t.device.script;
    }
    m_tool[handle++] = i;
  }
  if (!kind)
    throw InputError(scene.file.string(), 0, "\"haptics\" needs an instrument to drive",
                     "a grasper or scissors with device = \"mouse\" or \"script:FILE\"");
  m_kind = *kind;
  std::array<haptics::Trocar, haptics::kHandles> trocars{};
  if (m_kind == DeviceKind::kScript) {
    ToolPath path = read_tool_path(*script);
    std::array<std::optional<std::size_t>, haptics::kHandles> of_handle{};
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
  } else {
    haptics::MouseMapping map;
    for (std::size_t h = 0; h < haptics::kHandles; ++h) {
      if (!m_tool[h]) continue;
      const MouseHandle mh = mouse_handle(scene.tools[*m_tool[h]], h, options.aim_m);
      trocars[h] = mh.trocar;
      map.rest[h] = mh.rest;
    }
    auto mouse = std::make_unique<haptics::MouseKeyboardDevice>(trocars, map);
    m_mouse = mouse.get();
    m_device = std::move(mouse);
  }
  haptics::HapticLoopConfig c;
  c.trocars = trocars;
  c.realtime = options.realtime;
  c.gap_monitor = options.realtime;
  m_loop = std::make_unique<haptics::HapticLoop>(*m_device, m_model, c);
}

HapticsStage::~HapticsStage() { stop(); }

void HapticsStage::stop() {
  if (m_loop && m_loop->running()) m_loop->stop();
}

haptics::LoopStatus HapticsStage::status() const { return m_loop->status().load(); }

void HapticsStage::feed_pointer(const haptics::PointerInput& in) noexcept {
  if (m_mouse != nullptr) m_mouse->feed(in);
}

void HapticsStage::step(const StepContext& ctx, SimState& state) {
  // Solver -> loop: the model of the state as it enters this step.
  haptics::ContactModel model;
  model.step = ctx.step + 1;  // 0 means "no model yet"
  model.time_s = ctx.time_s;
  for (std::size_t h = 0; h < haptics::kHandles; ++h) {
    if (!m_tool[h] || *m_tool[h] >= state.tools.size()) continue;
    haptics::ToolContact& tc = model.tools[h];
    tc.sim_tip_m = state.tools[*m_tool[h]].tip_m;
    if (m_contact != nullptr) {
      const std::optional<haptics::ContactPlane> plane = m_contact->haptic_plane(*m_tool[h]);
      if (plane) {
        tc.contacts[0] = *plane;
        tc.n_contacts = 1;
      }
    }
  }
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
  nlohmann::json j = nlohmann::json::parse(os.str());
  j["device"] = std::string(device_kind_name(m_kind));
  return j;
}

}  // namespace serosa::app
