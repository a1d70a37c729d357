#include "render/key_clock.h"

#include <algorithm>

namespace serosa::render {

void KeyClock::poll(double now_s) {
  m_previous_poll_s = m_poll_s;
  m_poll_s = now_s;
}

void KeyClock::press(std::size_t key) {
  if (key >= m_down.size() || m_down[key]) return;
  m_down[key] = true;
  m_down_at_s[key] = m_poll_s;
}

double KeyClock::release(std::size_t key) {
  if (key >= m_down.size() || !m_down[key]) return -1.0;
  m_down[key] = false;
  // Pressed and let go within one poll's batch: the previous poll came before the press.
  return std::max(0.0, m_previous_poll_s - m_down_at_s[key]);
}

double KeyClock::held_s(std::size_t key, double now_s) const {
  if (key >= m_down.size() || !m_down[key]) return -1.0;
  return std::max(0.0, now_s - m_down_at_s[key]);
}

}  // namespace serosa::render
