#include "engine/mesh_quality.h"

#include <algorithm>
#include <array>
#include <cmath>

namespace serosa {

double tet_quality(const Vec3& a, const Vec3& b, const Vec3& c, const Vec3& d) {
  // Edge vectors, scaled by their largest coordinate so that neither tiny (underflow of V) nor
  // huge (overflow of V^2) meshes lose the answer; the measure is scale invariant anyway.
  std::array<Vec3, 6> e{b - a, c - a, d - a, c - b, d - b, d - c};
  double scale = 0.0;
  for (const Vec3& v : e) scale = std::max(scale, v.cwiseAbs().maxCoeff());
  if (!std::isfinite(scale)) return std::nan("");
  if (scale <= 0.0) return 0.0;  // all four nodes coincide: no shape at all, call it flat
  for (Vec3& v : e) v /= scale;
  const double vol = e[0].dot(e[1].cross(e[2])) / 6.0;  // signed volume, as signed_volume()
  double sum_sq = 0.0;
  for (const Vec3& v : e) sum_sq += v.squaredNorm();
  const double r = std::cbrt(3.0 * std::abs(vol));  // (3|V|)^(2/3) = r^2
  // Rounding can push a regular tet a hair above 1; the measure is bounded by 1 in exact math.
  const double q = std::min(12.0 * r * r / sum_sq, 1.0);
  return vol < 0.0 ? -q : q;
}

std::vector<double> tet_qualities(std::span<const Vec3> positions, std::span<const Tet> tets) {
  std::vector<double> q(tets.size());
  for (std::size_t i = 0; i < tets.size(); ++i) {
    const Tet& t = tets[i];
    q[i] = tet_quality(
        positions[static_cast<std::size_t>(t[0])], positions[static_cast<std::size_t>(t[1])],
        positions[static_cast<std::size_t>(t[2])], positions[static_cast<std::size_t>(t[3])]);
  }
  return q;
}

std::vector<double> tet_qualities(const TetMesh& mesh) {
  return tet_qualities(mesh.rest, mesh.tets);
}

}  // namespace serosa
