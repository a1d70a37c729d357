#include "haptics/trocar_kinematics.h"

#include <algorithm>
#include <cmath>

namespace serosa::haptics {
namespace {

// Shaft direction in the trocar frame: Ry(yaw) Rx(pitch) e_z.
Vec3 local_shaft(double pitch, double yaw) {
  return {std::cos(pitch) * std::sin(yaw), -std::sin(pitch), std::cos(pitch) * std::cos(yaw)};
}

}  // namespace

Quat tool_rotation(const Trocar& t, const JointState& q) {
  const Quat r = t.rotation * Quat(Eigen::AngleAxisd(q.yaw_rad, Vec3::UnitY())) *
                 Quat(Eigen::AngleAxisd(q.pitch_rad, Vec3::UnitX())) *
                 Quat(Eigen::AngleAxisd(q.roll_rad, Vec3::UnitZ()));
  return r.normalized();
}

ToolState forward(const Trocar& t, const JointState& q) {
  const Quat r = tool_rotation(t, q);
  const Vec3 tip = t.pivot_m + q.insertion_m * (r * Vec3::UnitZ());
  ToolState s;
  s.tip_m = {tip.x(), tip.y(), tip.z()};
  s.quat_wxyz = {r.w(), r.x(), r.y(), r.z()};
  s.jaw_rad = q.jaw_rad;
  return s;
}

JointState inverse(const Trocar& t, const ToolState& s) {
  const Quat r = Quat(s.quat_wxyz[0], s.quat_wxyz[1], s.quat_wxyz[2], s.quat_wxyz[3]).normalized();
  const Mat3 m = (t.rotation.conjugate() * r).toRotationMatrix();
  JointState q;
  q.pitch_rad = std::asin(std::clamp(-m(1, 2), -1.0, 1.0));
  q.yaw_rad = std::atan2(m(0, 2), m(2, 2));
  q.roll_rad = std::atan2(m(1, 0), m(1, 1));
  const Vec3 tip(s.tip_m[0], s.tip_m[1], s.tip_m[2]);
  q.insertion_m = (tip - t.pivot_m).dot(r * Vec3::UnitZ());
  q.jaw_rad = s.jaw_rad;
  return q;
}

JointState inverse_from_tip(const Trocar& t, const Vec3& tip_m, const JointState& previous) {
  JointState q = previous;
  const Vec3 local = t.rotation.conjugate() * (tip_m - t.pivot_m);
  const double n = local.norm();
  q.insertion_m = n;
  if (!(n > 1e-9)) {  // at the pivot (or NaN input): keep the previous direction
    q.insertion_m = std::isfinite(n) ? n : previous.insertion_m;
    return q;
  }
  const Vec3 d = local / n;
  q.pitch_rad = std::asin(std::clamp(-d.y(), -1.0, 1.0));
  q.yaw_rad = std::atan2(d.x(), d.z());
  return q;
}

Mat3 tip_jacobian(const Trocar& t, const JointState& q) {
  const double a = q.yaw_rad;
  const double b = q.pitch_rad;
  const double s = q.insertion_m;
  const Mat3 r0 = t.rotation.toRotationMatrix();
  Mat3 j;
  j.col(0) = s * (r0 * Vec3(-std::sin(b) * std::sin(a), -std::cos(b), -std::sin(b) * std::cos(a)));
  j.col(1) = s * (r0 * Vec3(std::cos(b) * std::cos(a), 0.0, -std::cos(b) * std::sin(a)));
  j.col(2) = r0 * local_shaft(b, a);
  return j;
}

JointEffort tip_to_joint(const Trocar& t, const JointState& q, const Vec3& force_N,
                         const Vec3& moment_Nm, double jaw_torque_Nm) {
  const Vec3 tau = tip_jacobian(t, q).transpose() * force_N;
  const Vec3 shaft = t.rotation * local_shaft(q.pitch_rad, q.yaw_rad);
  JointEffort e;
  e.pitch_Nm = tau.x();
  e.yaw_Nm = tau.y();
  e.insertion_N = tau.z();
  e.roll_Nm = moment_Nm.dot(shaft);
  e.jaw_Nm = jaw_torque_Nm;
  return e;
}

Vec3 tip_to_handle_force(const Trocar& t, const JointState& q, const Vec3& force_N) {
  const Vec3 d = t.rotation * local_shaft(q.pitch_rad, q.yaw_rad);
  const Vec3 axial = force_N.dot(d) * d;
  const Vec3 lateral = force_N - axial;
  return axial - (q.insertion_m / t.handle_length_m) * lateral;
}

Vec3 pivot_moment(const Trocar& t, const JointState& q, const Vec3& force_N) {
  const Vec3 r = q.insertion_m * (t.rotation * local_shaft(q.pitch_rad, q.yaw_rad));
  return r.cross(force_N);
}

}  // namespace serosa::haptics
