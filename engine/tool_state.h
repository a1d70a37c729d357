// ToolState: one instrument's pose as the solver consumes it at a step boundary.
#pragma once

#include <array>
#include <cstdint>
#include <type_traits>

namespace serosa {

/// One tool's input, trivially copyable so it crosses threads through a Seqlock and is recorded
/// byte for byte. Plain arrays, not Eigen types, to keep the layout fixed.
struct ToolState {
  std::uint64_t tick = 0;                      ///< haptic tick (1 ms) or scripted sample index
  double time_s = 0.0;                         ///< time of the sample, s
  std::array<double, 3> tip_m{0.0, 0.0, 0.0};  ///< tool tip position, m (scene frame)
  std::array<double, 4> quat_wxyz{1.0, 0.0, 0.0, 0.0};  ///< orientation, unit quaternion
  double jaw_rad = 0.0;                                 ///< jaw opening angle, rad (0 = closed)
  std::uint32_t buttons = 0;                            ///< device buttons bit mask
};
static_assert(std::is_trivially_copyable_v<ToolState>);

}  // namespace serosa
