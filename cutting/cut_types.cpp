#include "cutting/cut_types.h"

#include "engine/geometry/tet_extent.h"

namespace serosa::cutting {

TetBoxQuery brute_force_query(const TetMesh& mesh) {
  return [&mesh](const Vec3& lo, const Vec3& hi, std::vector<std::int32_t>& out) {
    for (std::int32_t i = 0; i < mesh.num_tets(); ++i) {
      Vec3 tlo, thi;
      geometry::tet_box(mesh, mesh.tets[i], tlo, thi);
      if ((tlo.array() <= hi.array()).all() && (thi.array() >= lo.array()).all()) out.push_back(i);
    }
  };
}

}  // namespace serosa::cutting
