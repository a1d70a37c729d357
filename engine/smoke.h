// Surgical smoke a hook's coagulation raises, as the smoke stage publishes it for the view
// (cutting/smoke_stage.h). Plain data, scene frame, SI units.
#pragma once

#include "engine/math.h"

namespace serosa {

/// One puff of smoke: a soft, roughly round cloud.
struct SmokePuff {
  Vec3 at_m = Vec3::Zero();  ///< its centre, m
  double radius_m = 0.0;     ///< m
  double density = 0.0;      ///< how much it hides what lies behind its centre, [0, 1]
};

}  // namespace serosa
