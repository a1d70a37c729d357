// The scene's surroundings as render::Scenery (see scenery_from_scene.h).
#include "app/scenery_from_scene.h"

#include "render/scenery.h"

namespace serosa::app {
namespace {

std::array<float, 3> to_float(const Vec3& v) {
  return {static_cast<float>(v.x()), static_cast<float>(v.y()), static_cast<float>(v.z())};
}

}  // namespace

render::Scenery scenery_from_scene(const Scene& scene, const TetMesh& mesh) {
  if (scene.render.surroundings != Surroundings::kAbdomen || scene.supports.empty() ||
      mesh.rest.empty())
    return {};
  Vec3 lo = mesh.rest.front(), hi = mesh.rest.front();
  for (const Vec3& p : mesh.rest) {
    lo = lo.cwiseMin(p);
    hi = hi.cwiseMax(p);
  }
  const Support& wall = scene.supports.front();
  render::AbdomenPlacement placement;
  placement.point_m = to_float(wall.point_m);
  placement.normal = to_float(wall.normal);
  placement.organs_lo_m = to_float(lo);
  placement.organs_hi_m = to_float(hi);
  // Without gravity (or along the wall's normal) make_abdomen picks an axis itself.
  placement.up_hint = to_float(-scene.settings.gravity_mps2);
  return render::make_abdomen(placement);
}

}  // namespace serosa::app
