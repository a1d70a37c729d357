// ScriptDevice: a scripted tool path (engine/scene/tool_path.h CSV) played in real time as a
// device. Time starts at the first poll. Each handle follows one tool of the path (or stays at
// rest); joints are recovered through the handle's trocar (inverse kinematics of the scripted
// pose).
#pragma once

#include <array>
#include <optional>

#include "engine/scene/tool_path.h"
#include "haptics/device.h"

namespace serosa::haptics {

class ScriptDevice final : public Device {
 public:
  /// tool_of_handle[h]: index into path.tools, or nullopt for an idle handle. Throws
  /// std::out_of_range when an index is not a tool of the path.
  ScriptDevice(ToolPath path, std::array<std::optional<std::size_t>, kHandles> tool_of_handle,
               std::array<Trocar, kHandles> trocars);

  bool poll(double now_s, DeviceSample& out) noexcept override;
  [[nodiscard]] bool connected() const noexcept override { return true; }
  void command(const DeviceCommand& c) noexcept override { m_last = c; }
  [[nodiscard]] const char* name() const noexcept override { return "script"; }

  /// Path time of the last sample, s.
  [[nodiscard]] double path_time_s() const noexcept { return m_path_t; }
  /// The last command received (tests).
  [[nodiscard]] const DeviceCommand& last_command() const noexcept { return m_last; }

 private:
  ToolPath m_path;
  std::array<std::optional<std::size_t>, kHandles> m_tool;
  std::array<Trocar, kHandles> m_trocars;
  bool m_started = false;
  double m_t0 = 0.0;
  double m_path_t = 0.0;
  std::uint64_t m_seq = 0;
  DeviceCommand m_last{};
};

}  // namespace serosa::haptics
