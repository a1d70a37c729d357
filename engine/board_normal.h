// Which way is up for what rests on the scene's board: the first support's normal, else against
// gravity, else +z. The transfer drill measures "across the board" in the plane normal to it; the
// clip target's marker stands along it.
#pragma once

#include "engine/math.h"
#include "engine/scene/scene.h"

namespace serosa {

[[nodiscard]] inline Vec3 board_normal(const Scene& scene) {
  if (!scene.supports.empty()) return scene.supports.front().normal;
  const Vec3 g = scene.settings.gravity_mps2;
  return g.norm() > 0.0 ? Vec3(-g.normalized()) : Vec3(Vec3::UnitZ());
}

}  // namespace serosa
