// How far a drawn (tessellated) surface is from a reference surface: the rest boundary of a tet
// mesh as a TriMesh, nearest-triangle distances to a fixed TriMesh through a uniform grid, and
// the max and mean over a mesh's vertices and centroids. Shared by bench/render
// (BM_OrganAccuracy) and `serosa bench tessellation`.
#pragma once

#include <array>
#include <cstdint>
#include <unordered_map>
#include <vector>

#include "engine/tet_mesh.h"
#include "render/phong_tessellation.h"

namespace serosa::render {

/// The boundary of `mesh` at rest: faces of one tet only, oriented away from the tet's fourth node
/// (outward); pos holds every node (unused ones are harmless), float, m.
[[nodiscard]] TriMesh rest_boundary(const TetMesh& mesh);

/// Nearest-triangle distances to a fixed triangle mesh (kept by reference: it must outlive this).
/// Triangles' boxes are binned in a uniform grid of about 2/3 of the mean edge; a query searches
/// growing shells of cells until no closer triangle can exist (up to 64 shells).
class SurfaceDistance {
 public:
  explicit SurfaceDistance(const TriMesh& reference);
  /// Distance (m) from p to the nearest reference triangle.
  [[nodiscard]] double operator()(const std::array<double, 3>& p) const;

 private:
  [[nodiscard]] std::array<double, 3> point(std::uint32_t v) const;
  [[nodiscard]] std::int64_t cell_of(double x, int d) const;
  static std::int64_t key(std::int64_t i, std::int64_t j, std::int64_t k);
  const TriMesh& m_;
  std::array<double, 3> lo_{};
  double cell_ = 1.0;
  std::unordered_map<std::int64_t, std::vector<std::uint32_t>> grid_;
};

/// Distance of `mesh` from the reference, sampled at every vertex and triangle centroid, m.
struct MeshDistance {
  double max_m = 0.0;
  double mean_m = 0.0;
};
[[nodiscard]] MeshDistance mesh_distance(const TriMesh& mesh, const SurfaceDistance& reference);

}  // namespace serosa::render
