// A tool pose for the tests: tip (m), orientation and jaw opening (rad), the rest zero.
#pragma once

#include "engine/math.h"
#include "engine/tool_state.h"

namespace serosa::test_support {

inline ToolState pose(const Vec3& tip, const Eigen::Quaterniond& q, double jaw) {
  ToolState ts;
  ts.tip_m = {tip.x(), tip.y(), tip.z()};
  ts.quat_wxyz = {q.w(), q.x(), q.y(), q.z()};
  ts.jaw_rad = jaw;
  return ts;
}

}  // namespace serosa::test_support
