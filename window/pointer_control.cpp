#include "window/pointer_control.h"

#include <algorithm>

#include "engine/hook.h"

namespace serosa::window {

const haptics::PointerInput& PointerControl::update(const PointerEvents& e,
                                                    const ScreenAxes& axes) {
  if (e.tab % 2 != 0) m_active = (m_active + 1) % haptics::kHandles;
  const std::size_t h = m_active;
  const Vec3 move = kDragMetresPerPixel * (e.drag_dx_px * axes.right - e.drag_dy_px * axes.up) +
                    kDepthMetresPerStep * (e.insert - e.retract) * axes.forward;
  for (int k = 0; k < 3; ++k) m_input.move_m[h][static_cast<std::size_t>(k)] += move[k];
  m_input.depth_steps[h] += e.scroll_steps;
  m_input.roll_steps[h] += e.roll_right - e.roll_left;
  if (e.pedal % 2 != 0) m_input.buttons[h] ^= kPedalButton;
  if (e.exchange > 0) {
    m_input.exchanges[h] += static_cast<std::uint32_t>(e.exchange);
    m_input.buttons[h] &= ~kPedalButton;  // the next instrument comes in with its pedal up
  }
  m_input.homes[h] += static_cast<std::uint32_t>(std::max(e.home, 0));
  update_jaw(e);
  return m_input;
}

namespace {

// Where held J has brought jaws that stood at `start` when it went down `held_s` ago.
double bitten(double start, double held_s) {
  if (held_s < kJawTapS) return start;
  return std::max(0.0, start - (held_s - kJawTapS) / kJawCloseS);
}

}  // namespace

void PointerControl::update_jaw(const PointerEvents& e) {
  double& jaw = m_input.jaw_fraction[m_active];
  if (e.jaw_presses > 0 && !m_jaw_holding) {
    m_jaw_holding = true;
    m_jaw_start = jaw;
  }
  if (!m_jaw_holding) return;
  if (e.jaw_held) {
    jaw = bitten(m_jaw_start, e.jaw_held_s);
    return;
  }
  // Let go: a tap toggles, a hold leaves the jaws where it brought them.
  m_jaw_holding = false;
  const double held = std::max(0.0, e.jaw_released_after_s);
  jaw = held < kJawTapS ? (m_jaw_start > 0.5 ? 0.0 : 1.0) : bitten(m_jaw_start, held);
}

}  // namespace serosa::window
