// The rigid motion that best carries one point set onto another (least squares, Kabsch): how a
// body embedded in tissue (a clip) follows the tissue around it.
#pragma once

#include <vector>

#include "engine/math.h"

namespace serosa::geometry {

/// p = rotation * q + translation.
struct RigidMotion {
  Mat3 rotation = Mat3::Identity();
  Vec3 translation = Vec3::Zero();  ///< m
};

/// The proper rotation R and translation t minimising sum |R from[i] + t - to[i]|^2 over the
/// pairs ((k) points each, m). With fewer than three points, or points on one line, the
/// rotation about that line is not defined: then the rotation is the identity and only the
/// centroids are matched. Empty input or mismatched sizes: the identity.
[[nodiscard]] RigidMotion fit_rigid_motion(const std::vector<Vec3>& from,
                                           const std::vector<Vec3>& to);

}  // namespace serosa::geometry
