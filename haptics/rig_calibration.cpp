#include "haptics/rig_calibration.h"

#include <cmath>
#include <cstdint>
#include <limits>

namespace serosa::haptics {
namespace {

std::int32_t round_i32(double v) {
  if (!std::isfinite(v)) return 0;
  const double lo = std::numeric_limits<std::int32_t>::min();
  const double hi = std::numeric_limits<std::int32_t>::max();
  return static_cast<std::int32_t>(std::lround(std::fmin(std::fmax(v, lo), hi)));
}

std::int16_t sat_i16(double v) {
  if (!std::isfinite(v)) return 0;
  const double r = std::round(v);
  if (r >= 32767.0) return 32767;
  if (r <= -32768.0) return -32768;
  return static_cast<std::int16_t>(r);
}

}  // namespace

JointState to_joints(const RigCalibration& c, const HandleCounts& h) noexcept {
  JointState q;
  q.pitch_rad = h.pitch / c.pitch_counts_per_rad;
  q.yaw_rad = h.yaw / c.yaw_counts_per_rad;
  q.roll_rad = h.roll / c.roll_counts_per_rad;
  q.insertion_m = h.insertion / c.insertion_counts_per_m;
  q.jaw_rad = h.jaw / c.jaw_counts_per_rad;
  return q;
}

HandleCounts to_counts(const RigCalibration& c, const JointState& q) noexcept {
  HandleCounts h;
  h.pitch = round_i32(q.pitch_rad * c.pitch_counts_per_rad);
  h.yaw = round_i32(q.yaw_rad * c.yaw_counts_per_rad);
  h.roll = round_i32(q.roll_rad * c.roll_counts_per_rad);
  h.insertion = round_i32(q.insertion_m * c.insertion_counts_per_m);
  h.jaw = round_i32(q.jaw_rad * c.jaw_counts_per_rad);
  return h;
}

HandleEffort to_wire(const JointEffort& e) noexcept {
  HandleEffort w;
  w.pitch_torque = sat_i16(e.pitch_Nm / kTorqueScaleNm);
  w.yaw_torque = sat_i16(e.yaw_Nm / kTorqueScaleNm);
  w.roll_torque = sat_i16(e.roll_Nm / kTorqueScaleNm);
  w.insertion_force = sat_i16(e.insertion_N / kForceScaleN);
  w.jaw_torque = sat_i16(e.jaw_Nm / kTorqueScaleNm);
  return w;
}

JointEffort from_wire(const HandleEffort& w) noexcept {
  JointEffort e;
  e.pitch_Nm = w.pitch_torque * kTorqueScaleNm;
  e.yaw_Nm = w.yaw_torque * kTorqueScaleNm;
  e.roll_Nm = w.roll_torque * kTorqueScaleNm;
  e.insertion_N = w.insertion_force * kForceScaleN;
  e.jaw_Nm = w.jaw_torque * kTorqueScaleNm;
  return e;
}

}  // namespace serosa::haptics
