#include "app/mouse_takeover.h"

#include <algorithm>
#include <cmath>
#include <cstring>

#include "app/replay_controller.h"
#include "engine/jaw_range.h"

namespace serosa::app {

MouseTakeover::MouseTakeover(const Scene& scene, const std::vector<ToolState>& tools,
                             const haptics::MouseMapping& mapping)
    : m_map(mapping) {
  std::size_t handle = 0;
  for (std::size_t i = 0; i < scene.tools.size() && i < tools.size(); ++i) {
    if (handle >= haptics::kHandles) break;
    if (scene.tools[i].kind == ToolKind::kEndoscope) continue;
    const std::size_t h = handle++;
    m_tool[h] = i;
    const ToolState& s = tools[i];
    const Quat q =
        Quat(s.quat_wxyz[0], s.quat_wxyz[1], s.quat_wxyz[2], s.quat_wxyz[3]).normalized();
    const Vec3 tip(s.tip_m[0], s.tip_m[1], s.tip_m[2]);
    const Vec3 shaft = q * Vec3::UnitZ();
    const double length =
        scene.tools[i].trocar_m ? std::max((tip - *scene.tools[i].trocar_m).norm(), 1e-3) : 0.1;
    m_trocars[h].pivot_m = tip - length * shaft;
    m_trocars[h].rotation = q;
    m_map.rest[h] = haptics::JointState{};
    m_map.rest[h].insertion_m = length;
    m_map.rest[h].jaw_rad = s.jaw_rad;
    m_map.max_insertion_m = std::max(m_map.max_insertion_m, 2.0 * length);
    m_map.min_insertion_m = std::min(m_map.min_insertion_m, length);
    m_map.jaw_max_rad[h] = std::max(max_jaw_rad(scene.tools[i].kind), s.jaw_rad);
    m_initial.jaw_fraction[h] = m_map.jaw_max_rad[h] > 0.0 ? s.jaw_rad / m_map.jaw_max_rad[h] : 0.0;
    m_initial.buttons[h] = s.buttons;
  }
  m_device = std::make_unique<haptics::MouseKeyboardDevice>(m_trocars, m_map);
}

void MouseTakeover::apply(const haptics::PointerInput& in, ReplayController& replay) {
  m_device->feed(in);
  haptics::DeviceSample sample;
  const double t = replay.time_s();
  if (!m_device->poll(t, sample)) return;
  for (std::size_t h = 0; h < haptics::kHandles; ++h) {
    if (!m_tool[h]) continue;
    // A fresh state with zero padding: the state hash covers the whole struct, and a replay reads
    // the recording into zeroed ToolStates.
    ToolState s;
    std::memset(static_cast<void*>(&s), 0, sizeof s);
    s.tip_m = sample.pose[h].tip_m;
    s.quat_wxyz = sample.pose[h].quat_wxyz;
    s.jaw_rad = sample.pose[h].jaw_rad;
    s.tick = replay.steps_taken();
    s.time_s = t;
    s.buttons = sample.buttons[h];
    replay.set_tool_input(*m_tool[h], s);
  }
}

}  // namespace serosa::app
