// RigCalibration: encoder counts <-> SI joint values, SI efforts <-> the force packet's fixed
// point.
#pragma once

#include <numbers>

#include "haptics/rig_protocol.h"
#include "haptics/trocar_kinematics.h"

namespace serosa::haptics {

/// Encoder scales of one rig (docs/rig-protocol.md). Defaults: 4096 counts per turn on every
/// angle, 20 counts per mm of insertion.
struct RigCalibration {
  double pitch_counts_per_rad = 4096.0 / (2.0 * std::numbers::pi);
  double yaw_counts_per_rad = 4096.0 / (2.0 * std::numbers::pi);
  double roll_counts_per_rad = 4096.0 / (2.0 * std::numbers::pi);
  double jaw_counts_per_rad = 4096.0 / (2.0 * std::numbers::pi);
  double insertion_counts_per_m = 20000.0;
};

/// Counts -> joints.
[[nodiscard]] JointState to_joints(const RigCalibration& c, const HandleCounts& h) noexcept;
/// Joints -> counts (rounded to nearest; used by the emulator).
[[nodiscard]] HandleCounts to_counts(const RigCalibration& c, const JointState& q) noexcept;
/// SI efforts -> packet fixed point, saturating at the int16 range; NaN becomes 0.
[[nodiscard]] HandleEffort to_wire(const JointEffort& e) noexcept;
/// Packet fixed point -> SI efforts.
[[nodiscard]] JointEffort from_wire(const HandleEffort& e) noexcept;

}  // namespace serosa::haptics
