#include "app/mouse_takeover.h"

#include <algorithm>
#include <cmath>
#include <cstring>

#include "app/replay_controller.h"

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
    m_map.max_insertion_m = std::max(m_map.max_insertion_m, 2.0 * length);
    m_jaw[h] = s.jaw_rad;
    m_initial.jaw_open[h] = s.jaw_rad > 0.5 * m_map.jaw_open_rad ? 1u : 0u;
    m_initial.buttons[h] = s.buttons;
  }
  m_device = std::make_unique<haptics::MouseKeyboardDevice>(m_trocars, m_map);
}

void MouseTakeover::apply(const haptics::PointerInput& in, ReplayController& replay) {
  m_device->feed(in);
  haptics::DeviceSample sample;
  const double t = replay.time_s();
  if (!m_device->poll(t, sample)) return;
  const double max_jaw_step = kJawSpeed * replay.dt_s();
  for (std::size_t h = 0; h < haptics::kHandles; ++h) {
    if (!m_tool[h]) continue;
    // A fresh state with zero padding: the state hash covers the whole struct, and a replay reads
    // the recording into zeroed ToolStates.
    ToolState s;
    std::memset(static_cast<void*>(&s), 0, sizeof s);
    s.tip_m = sample.pose[h].tip_m;
    s.quat_wxyz = sample.pose[h].quat_wxyz;
    // The jaws hold the recorded opening until the input's jaw flag first changes.
    m_jaw_moved[h] = m_jaw_moved[h] || in.jaw_open[h] != m_initial.jaw_open[h];
    if (m_jaw_moved[h]) {
      const double target = in.jaw_open[h] ? m_map.jaw_open_rad : 0.0;
      m_jaw[h] += std::clamp(target - m_jaw[h], -max_jaw_step, max_jaw_step);
    }
    s.jaw_rad = m_jaw[h];
    s.tick = replay.steps_taken();
    s.time_s = t;
    s.buttons = sample.buttons[h];
    replay.set_tool_input(*m_tool[h], s);
  }
}

}  // namespace serosa::app
