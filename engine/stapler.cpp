#include "engine/stapler.h"

#include <algorithm>
#include <cmath>

#include "engine/tool_geometry.h"

namespace serosa {

std::optional<double> StaplerTrigger::update(double jaw_rad) {
  widest_rad = std::max(widest_rad, jaw_rad);
  if (!(jaw_rad <= kStaplerFireRad) || widest_rad < kStaplerArmRad) return std::nullopt;
  const double fired_from = widest_rad;
  widest_rad = jaw_rad;  // the next fire needs the jaws opened again
  return fired_from;
}

StaplerJaws stapler_jaws(const ToolState& tool, double opening_rad) {
  const ToolFrame f = tool_frame(tool);
  StaplerJaws j;
  j.hinge = f.hinge;
  j.frame.col(0) = f.side;
  j.frame.col(1) = f.pin;
  j.frame.col(2) = f.forward;
  j.opening_rad = opening_rad;
  return j;
}

Vec3 stapler_local(const StaplerJaws& jaws, const Vec3& p) {
  return jaws.frame.transpose() * (p - jaws.hinge);
}

namespace {

double half_tan(const StaplerJaws& jaws) {
  return std::tan(0.5 * std::clamp(jaws.opening_rad, 0.0, 3.0));
}

}  // namespace

bool in_stapled_wedge(const StaplerJaws& jaws, const Vec3& local) {
  if (local.z() < kStapleStart || local.z() > kCartridgeLength) return false;
  return std::abs(local.x()) <= local.z() * half_tan(jaws);
}

int staple_line_of(const Vec3& local) {
  const double d = std::abs(local.y());
  if (std::abs(d - kStapleLineOffset) > kStapleLineHalfWidth) return -1;
  return local.y() < 0.0 ? 0 : 1;
}

Vec3 staple_line_hinge(const StaplerJaws& jaws, int k) {
  return jaws.hinge + (k == 0 ? -kStapleLineOffset : kStapleLineOffset) * jaws.frame.col(1);
}

std::array<Vec3, 4> knife_polygon(const StaplerJaws& jaws) {
  const double t = half_tan(jaws);
  const auto at = [&](double along, double across) {
    return Vec3(jaws.hinge + along * jaws.frame.col(2) + across * jaws.frame.col(0));
  };
  return {at(kStapleStart, -kStapleStart * t), at(kCartridgeLength, -kCartridgeLength * t),
          at(kCartridgeLength, kCartridgeLength * t), at(kStapleStart, kStapleStart * t)};
}

// The region is the intersection of six half-spaces n.l <= d (in the jaws' frame), each moved
// out by r: the segment is clipped against each in turn (Cyrus-Beck).
bool segment_meets_stapled_region(const StaplerJaws& jaws, const Vec3& a, const Vec3& b, double r) {
  const Vec3 la = stapler_local(jaws, a), lb = stapler_local(jaws, b);
  const double t = half_tan(jaws);
  const double slant = std::sqrt(1.0 + t * t);  // |(1, 0, -t)|
  const double pin = kStapleLineOffset + kStapleLineHalfWidth;
  const std::array<std::pair<Vec3, double>, 6> planes{{
      {Vec3(0, 0, -1), -kStapleStart + r},
      {Vec3(0, 0, 1), kCartridgeLength + r},
      {Vec3(0, 1, 0), pin + r},
      {Vec3(0, -1, 0), pin + r},
      {Vec3(1, 0, -t), r * slant},
      {Vec3(-1, 0, -t), r * slant},
  }};
  double t0 = 0.0, t1 = 1.0;
  for (const auto& [n, d] : planes) {
    const double fa = n.dot(la) - d, fb = n.dot(lb) - d;  // <= 0 inside
    if (fa > 0.0 && fb > 0.0) return false;
    if (fa > 0.0) t0 = std::max(t0, fa / (fa - fb));
    if (fb > 0.0) t1 = std::min(t1, fa / (fa - fb));
    if (t0 > t1) return false;
  }
  return true;
}

}  // namespace serosa
