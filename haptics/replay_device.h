// ReplayDevice: plays back recorded DeviceSamples in real time (their time_s relative to the
// first one; playback time starts at the first poll). Each poll returns the newest sample that is
// due; samples whose time passed during a stall are skipped, never replayed in a burst. After the
// last sample no new ones arrive (the loop then zeroes the force after device_timeout_s).
#pragma once

#include <vector>

#include "haptics/device.h"

namespace serosa::haptics {

class ReplayDevice final : public Device {
 public:
  /// samples: in non-decreasing time_s order (throws std::invalid_argument otherwise).
  explicit ReplayDevice(std::vector<DeviceSample> samples);

  bool poll(double now_s, DeviceSample& out) noexcept override;
  [[nodiscard]] bool connected() const noexcept override { return true; }
  void command(const DeviceCommand& c) noexcept override { m_last = c; }
  [[nodiscard]] const char* name() const noexcept override { return "replay"; }

  /// Index of the next sample not yet delivered.
  [[nodiscard]] std::size_t cursor() const noexcept { return m_next; }
  [[nodiscard]] bool finished() const noexcept { return m_next >= m_samples.size(); }
  [[nodiscard]] const DeviceCommand& last_command() const noexcept { return m_last; }

 private:
  std::vector<DeviceSample> m_samples;
  std::size_t m_next = 0;
  bool m_started = false;
  double m_t0 = 0.0;
  DeviceCommand m_last{};
};

}  // namespace serosa::haptics
