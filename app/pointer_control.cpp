#include "app/pointer_control.h"

#include <algorithm>

#include "engine/hook.h"

namespace serosa::app {

const haptics::PointerInput& PointerControl::update(const PointerEvents& e, const ScreenAxes& axes,
                                                    double now_s) {
  if (e.tab % 2 != 0) m_active = (m_active + 1) % haptics::kHandles;
  const std::size_t h = m_active;
  const Vec3 move = kDragMetresPerPixel * (e.drag_dx_px * axes.right - e.drag_dy_px * axes.up) +
                    kDepthMetresPerStep * (e.insert - e.retract) * axes.forward;
  for (int k = 0; k < 3; ++k) m_input.move_m[h][static_cast<std::size_t>(k)] += move[k];
  m_input.depth_steps[h] += e.scroll_steps;
  m_input.roll_steps[h] += e.roll_right - e.roll_left;
  if (e.pedal % 2 != 0) m_input.buttons[h] ^= kPedalButton;
  m_input.homes[h] += static_cast<std::uint32_t>(std::max(e.home, 0));
  update_jaw(e, now_s);
  return m_input;
}

void PointerControl::update_jaw(const PointerEvents& e, double now_s) {
  double& jaw = m_input.jaw_fraction[m_active];
  if (e.jaw_presses > 0 && !m_jaw_holding) {
    m_jaw_holding = true;
    m_jaw_t0 = now_s;
    m_jaw_start = jaw;
  }
  if (!m_jaw_holding) return;
  const double held = now_s - m_jaw_t0;
  if (!e.jaw_held) {  // let go: a tap toggles, a hold leaves the jaws where they are
    m_jaw_holding = false;
    if (held < kJawTapS) jaw = m_jaw_start > 0.5 ? 0.0 : 1.0;
    return;
  }
  if (held >= kJawTapS) jaw = std::max(0.0, m_jaw_start - (held - kJawTapS) / kJawCloseS);
}

}  // namespace serosa::app
