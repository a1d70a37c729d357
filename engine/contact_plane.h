// ContactPlane: a local model of the tissue around a tool tip, what the contact stage hands to the
// haptic loop (haptics/contact_model.h carries it across threads). Plain data, SI units.
#pragma once

#include <array>

namespace serosa {

/// One local contact: a half-space {x : (point - x) . normal <= 0} of the tissue around the
/// contact. A proxy at depth d = (point - x) . normal > 0 feels stiffness * d along normal.
struct ContactPlane {
  std::array<double, 3> point_m{0.0, 0.0, 0.0};  ///< a point on the tissue surface, scene, m
  std::array<double, 3> normal{0.0, 0.0, 1.0};   ///< unit outward normal (towards the tool)
  double stiffness_Npm = 0.0;                    ///< local contact stiffness, N/m (>= 0)
};

}  // namespace serosa
