#include "haptics/replay_device.h"

#include <stdexcept>
#include <utility>

namespace serosa::haptics {

ReplayDevice::ReplayDevice(std::vector<DeviceSample> samples) : m_samples(std::move(samples)) {
  for (std::size_t i = 1; i < m_samples.size(); ++i) {
    if (!(m_samples[i].time_s >= m_samples[i - 1].time_s)) {
      throw std::invalid_argument("ReplayDevice: sample " + std::to_string(i) +
                                  " goes back in time (time_s must not decrease)");
    }
  }
}

bool ReplayDevice::poll(double now_s, DeviceSample& out) noexcept {
  if (m_samples.empty()) return false;
  if (!m_started) {
    m_started = true;
    m_t0 = now_s;
  }
  const double t = now_s - m_t0 + m_samples.front().time_s;
  std::size_t last_due = m_next;
  bool any = false;
  while (m_next < m_samples.size() && m_samples[m_next].time_s <= t) {
    last_due = m_next;
    ++m_next;
    any = true;
  }
  if (!any) return false;
  out = m_samples[last_due];
  out.time_s = now_s;
  return true;
}

}  // namespace serosa::haptics
