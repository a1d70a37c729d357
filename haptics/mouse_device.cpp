#include "haptics/mouse_device.h"

#include <algorithm>

namespace serosa::haptics {

bool MouseKeyboardDevice::poll(double now_s, DeviceSample& out) noexcept {
  const PointerInput in = m_input.load();
  DeviceSample s;
  s.sequence = ++m_seq;
  s.time_s = now_s;
  for (std::size_t h = 0; h < kHandles; ++h) {
    JointState q = m_map.rest[h];
    q.yaw_rad += in.dx_px[h] * m_map.rad_per_px;
    q.pitch_rad = std::clamp(q.pitch_rad + in.dy_px[h] * m_map.rad_per_px, -m_map.max_pitch_rad,
                             m_map.max_pitch_rad);
    q.insertion_m = std::clamp(q.insertion_m + in.scroll_steps[h] * m_map.m_per_step, 0.0,
                               m_map.max_insertion_m);
    q.roll_rad += in.roll_steps[h] * m_map.rad_per_step;
    q.jaw_rad = in.jaw_open[h] ? m_map.jaw_open_rad : 0.0;
    s.joints[h] = q;
    s.pose[h] = forward(m_trocars[h], q);
    s.buttons[h] = in.buttons[h];
  }
  out = s;
  return true;
}

}  // namespace serosa::haptics
