// Random trocars and joints for the trocar kinematics' property tests.
#pragma once

#include <random>

#include "haptics/trocar_kinematics.h"

namespace serosa::haptics {

inline Trocar random_trocar(std::mt19937& rng) {
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  Trocar t;
  t.pivot_m = Vec3(u(rng), u(rng), u(rng)) * 0.2;
  t.rotation =
      Quat(Eigen::AngleAxisd(3.0 * u(rng), Vec3(u(rng), u(rng), u(rng) + 2.0).normalized()));
  t.handle_length_m = 0.15 + 0.1 * (u(rng) + 1.0);
  return t;
}

inline JointState random_joints(std::mt19937& rng) {
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  JointState q;
  q.pitch_rad = 1.3 * u(rng);
  q.yaw_rad = 3.0 * u(rng);
  q.roll_rad = 3.0 * u(rng);
  q.insertion_m = 0.15 * (u(rng) + 1.0);
  q.jaw_rad = 0.5 * (u(rng) + 1.0);
  return q;
}

}  // namespace serosa::haptics
