#include "batch/run_gate.h"

namespace serosa::batch {

void RunGate::enter(bool alone) {
  std::unique_lock<std::mutex> lock(m_mutex);
  if (alone) {
    ++m_waiting_alone;
    m_changed.wait(lock, [&] { return !m_alone && m_shared == 0; });
    --m_waiting_alone;
    m_alone = true;
  } else {
    m_changed.wait(lock, [&] { return !m_alone && m_waiting_alone == 0; });
    ++m_shared;
  }
}

void RunGate::leave(bool alone) {
  {
    const std::lock_guard<std::mutex> lock(m_mutex);
    if (alone)
      m_alone = false;
    else
      --m_shared;
  }
  m_changed.notify_all();
}

}  // namespace serosa::batch
