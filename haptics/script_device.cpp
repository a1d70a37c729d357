#include "haptics/script_device.h"

#include <stdexcept>
#include <utility>

namespace serosa::haptics {

ScriptDevice::ScriptDevice(ToolPath path,
                           std::array<std::optional<std::size_t>, kHandles> tool_of_handle,
                           std::array<Trocar, kHandles> trocars)
    : m_path(std::move(path)), m_tool(tool_of_handle), m_trocars(trocars) {
  for (const auto& t : m_tool) {
    if (t && *t >= m_path.tools.size()) {
      throw std::out_of_range("ScriptDevice: tool index " + std::to_string(*t) +
                              " is not a tool of " + m_path.file);
    }
  }
}

bool ScriptDevice::poll(double now_s, DeviceSample& out) noexcept {
  if (!m_started) {
    m_started = true;
    m_t0 = now_s;
  }
  m_path_t = now_s - m_t0;
  DeviceSample s;
  s.sequence = ++m_seq;
  s.time_s = now_s;
  for (std::size_t h = 0; h < kHandles; ++h) {
    if (m_tool[h]) {
      // sample() does not allocate; the index was validated in the constructor.
      s.pose[h] = sample(m_path, *m_tool[h], m_path_t);
      s.joints[h] = inverse(m_trocars[h], s.pose[h]);
    } else {
      s.pose[h] = forward(m_trocars[h], JointState{});
    }
  }
  out = s;
  return true;
}

}  // namespace serosa::haptics
