#include "engine/instrument_hold.h"

#include "engine/tool_geometry.h"

namespace serosa {

ToolState port_pose(const Vec3& pivot_m, const Vec3& into_body) {
  ToolState s;
  const Vec3 d = into_body.norm() > 1e-12 ? into_body.normalized() : Vec3(Vec3::UnitZ());
  const Vec3 tip = pivot_m - kPortOutsideM * d;
  s.tip_m = {tip.x(), tip.y(), tip.z()};
  const Quat q = Quat::FromTwoVectors(Vec3::UnitZ(), d);
  s.quat_wxyz = {q.w(), q.x(), q.y(), q.z()};
  s.jaw_rad = 0.0;
  set_in_port(s, true);
  return s;
}

ToolState port_pose(const Tool& tool, const ToolState& inside) {
  const ToolFrame f = tool_frame(inside);
  if (!tool.trocar_m) return port_pose(f.tip - (0.1 - kPortOutsideM) * f.forward, f.forward);
  const Vec3 axis = f.tip - *tool.trocar_m;
  return port_pose(*tool.trocar_m, axis.norm() > 1e-6 ? axis : f.forward);
}

}  // namespace serosa
