#include "engine/scope_view.h"

#include <array>
#include <cmath>
#include <numbers>

namespace serosa {

double scope_angle_deg(const ToolState& scope) {
  return (scope.buttons & kScopeAngledButton) != 0 ? kScopeAngleDeg : 0.0;
}

bool scope_posed(const ToolState& scope) {
  return scope.tip_m != std::array<double, 3>{0.0, 0.0, 0.0} ||
         scope.quat_wxyz != std::array<double, 4>{1.0, 0.0, 0.0, 0.0};
}

ScopeView scope_view(const ToolState& scope) {
  Quat q(scope.quat_wxyz[0], scope.quat_wxyz[1], scope.quat_wxyz[2], scope.quat_wxyz[3]);
  q = q.norm() > 1e-12 ? q.normalized() : Quat::Identity();
  const Mat3 r = q.toRotationMatrix();
  const double a = scope_angle_deg(scope) * std::numbers::pi / 180.0;
  ScopeView v;
  v.eye = Vec3(scope.tip_m[0], scope.tip_m[1], scope.tip_m[2]);
  // Tilted about the scope's own x axis: its +z towards -y.
  v.dir = std::cos(a) * r.col(2) - std::sin(a) * r.col(1);
  v.up = std::sin(a) * r.col(2) + std::cos(a) * r.col(1);
  v.half_angle_rad = 0.5 * kScopeFovDeg * std::numbers::pi / 180.0;
  return v;
}

bool in_view(const ScopeView& view, const Vec3& p) {
  const Vec3 d = p - view.eye;
  const double n = d.norm();
  return n > 0.0 && d.dot(view.dir) >= n * std::cos(view.half_angle_rad);
}

}  // namespace serosa
