// Blood from a cut, unsecured artery, as the bleeding stage publishes it for the view
// (metrics/bleeding_stage.h). Plain data, scene frame, SI units.
#pragma once

#include "engine/math.h"

namespace serosa {

struct Blood {
  Vec3 source_m = Vec3::Zero();      ///< the cut end the stream leaves from, m (moves with it)
  Vec3 pool_m = Vec3::Zero();        ///< the centre of the pool it made, m
  Vec3 pool_normal = Vec3::UnitY();  ///< unit: the normal of the surface the pool lies on
  double pool_radius_m = 0.0;        ///< m
  /// The stream's strength now, [0, 1], pulsing with the heart; 0 once a ligature or the hook's
  /// coagulation closed the artery.
  double pulse = 0.0;
  double since_s = 0.0;  ///< when the bleeding began, s
  double shed_m3 = 0.0;  ///< blood shed so far, m^3
};

}  // namespace serosa
