#include "window/scope_control.h"

#include <algorithm>
#include <cstring>

#include "engine/scope_view.h"
#include "render/window.h"

namespace serosa::window {

ScopeControl::ScopeControl(const Tool& tool, const ToolState& start, const ScopeMapping& mapping)
    : m_map(mapping) {
  const Quat q =
      Quat(start.quat_wxyz[0], start.quat_wxyz[1], start.quat_wxyz[2], start.quat_wxyz[3])
          .normalized();
  const Vec3 tip(start.tip_m[0], start.tip_m[1], start.tip_m[2]);
  const Vec3 shaft = q * Vec3::UnitZ();
  // The shaft passes through the port: the pivot is the point of the shaft's line nearest the
  // scene's trocar (the script's scope may not aim exactly through it).
  const double length = tool.trocar_m ? std::max((tip - *tool.trocar_m).dot(shaft), 1e-3) : 0.1;
  m_trocar.pivot_m = tip - length * shaft;
  m_trocar.rotation = q;
  m_joints.insertion_m = length;
  move(0.0, 0.0, 0.0, 0.0);  // the start pose, for the solver's first step
}

void ScopeControl::move(double d_pitch, double d_yaw, double d_insertion, double d_roll) {
  m_joints.pitch_rad =
      std::clamp(m_joints.pitch_rad + d_pitch, -m_map.max_pitch_rad, m_map.max_pitch_rad);
  m_joints.yaw_rad += d_yaw;
  m_joints.insertion_m = std::max(m_joints.insertion_m + d_insertion, 0.0);
  m_joints.roll_rad += d_roll;
  // A fresh state with zero padding: the state hash covers the whole struct.
  ToolState s;
  std::memset(static_cast<void*>(&s), 0, sizeof s);
  const ToolState f = haptics::forward(m_trocar, m_joints);
  s.tip_m = f.tip_m;
  s.quat_wxyz = f.quat_wxyz;
  s.buttons = m_buttons;
  s.tick = ++m_changes;
  m_pose.store(s);
}

void ScopeControl::toggle_optic() {
  m_buttons ^= kScopeAngledButton;
  move(0.0, 0.0, 0.0, 0.0);
}

void ScopeControl::update(render::Window& window) {
  double pitch = 0.0, yaw = 0.0, insertion = 0.0, roll = 0.0;
  if (window.pressed(render::Key::kI)) insertion += m_map.m_per_press;
  if (window.pressed(render::Key::kK)) insertion -= m_map.m_per_press;
  if (window.pressed(render::Key::kComma)) roll -= m_map.rad_per_press;
  if (window.pressed(render::Key::kPeriod)) roll += m_map.rad_per_press;
  if (window.pressed(render::Key::kO)) toggle_optic();
  float x = 0.0f;
  float y = 0.0f;
  window.cursor(x, y);
  const bool down = window.right_mouse_down();
  if (down && m_dragging) {
    yaw += static_cast<double>(x - m_x) * m_map.rad_per_px;
    pitch += static_cast<double>(y - m_y) * m_map.rad_per_px;
  }
  m_dragging = down;
  m_x = x;
  m_y = y;
  if (pitch != 0.0 || yaw != 0.0 || insertion != 0.0 || roll != 0.0)
    move(pitch, yaw, insertion, roll);
}

}  // namespace serosa::window
