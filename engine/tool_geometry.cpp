#include "engine/tool_geometry.h"

#include <algorithm>
#include <cmath>

namespace serosa {

ToolFrame tool_frame(const ToolState& tool, double jaw_length_m) {
  Eigen::Quaterniond q(tool.quat_wxyz[0], tool.quat_wxyz[1], tool.quat_wxyz[2], tool.quat_wxyz[3]);
  if (!(q.norm() > 0.0)) q = Eigen::Quaterniond::Identity();
  q.normalize();
  const Mat3 r = q.toRotationMatrix();
  ToolFrame f;
  f.tip = Vec3(tool.tip_m[0], tool.tip_m[1], tool.tip_m[2]);
  f.side = r.col(0);
  f.pin = r.col(1);
  f.forward = r.col(2);
  f.hinge = f.tip - jaw_length_m * f.forward;
  return f;
}

Vec3 jaw_tip(const ToolFrame& frame, double jaw_rad, int k, double jaw_length_m) {
  const double a = 0.5 * jaw_rad;
  const double s = k == 0 ? 1.0 : -1.0;
  return frame.hinge + jaw_length_m * (std::cos(a) * frame.forward + s * std::sin(a) * frame.side);
}

double distance_to_segment(const Vec3& p, const Vec3& a, const Vec3& b) {
  const Vec3 ab = b - a;
  const double len2 = ab.squaredNorm();
  const double t = len2 > 0.0 ? std::clamp((p - a).dot(ab) / len2, 0.0, 1.0) : 0.0;
  return (p - (a + t * ab)).norm();
}

bool between_jaws(const ToolFrame& frame, double jaw_rad, const Vec3& p, double half_thickness_m,
                  double jaw_length_m) {
  const Vec3 d = p - frame.hinge;
  if (std::abs(d.dot(frame.pin)) > half_thickness_m) return false;
  const double a = d.dot(frame.forward), b = d.dot(frame.side);
  if (!(a > 0.0) || a * a + b * b > jaw_length_m * jaw_length_m) return false;
  return std::abs(std::atan2(b, a)) <= 0.5 * jaw_rad;
}

}  // namespace serosa
