// Math types shared by every floor. Units are SI (m, kg, s, N, Pa) unless a name says otherwise.
#pragma once

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <array>
#include <cstdint>

namespace serosa {

using Vec3 = Eigen::Vector3d;  ///< a point or vector in R^3 (m, m/s, N ... as named)
using Mat3 = Eigen::Matrix3d;
using Quat = Eigen::Quaterniond;

using Tet = std::array<std::int32_t, 4>;  ///< four node ids, positive orientation in rest space
using Tri = std::array<std::int32_t, 3>;  ///< three node ids

/// Signed volume of the tet (a, b, c, d) in m^3: positive when (b-a, c-a, d-a) is right-handed.
inline double signed_volume(const Vec3& a, const Vec3& b, const Vec3& c, const Vec3& d) {
  return (b - a).dot((c - a).cross(d - a)) / 6.0;
}

}  // namespace serosa
