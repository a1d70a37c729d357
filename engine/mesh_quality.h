// Tetrahedron shape quality: the mean-ratio measure, signed so that inverted tets read negative.
#pragma once

#include <span>
#include <vector>

#include "engine/math.h"
#include "engine/tet_mesh.h"

namespace serosa {

/// Mean-ratio quality of the tet (a, b, c, d) (Liu & Joe 1994):
///   q = sign(V) * 12 * (3 |V|)^(2/3) / sum_{i<j} |p_i - p_j|^2
/// where V is the signed volume (engine/math.h). q = 1 for a regular tet, 0 < q < 1 for any other
/// positively oriented tet, 0 for a flat one (and for coincident nodes), -1 <= q < 0 for an
/// inverted one. Dimensionless: invariant under rigid motions and uniform scaling.
/// Computed on edges scaled to unit size, so tiny and huge meshes read alike. Non-finite
/// coordinates give NaN.
/// @param a,b,c,d node positions, m
[[nodiscard]] double tet_quality(const Vec3& a, const Vec3& b, const Vec3& c, const Vec3& d);

/// tet_quality of every tet over the given positions.
/// @param positions (n) node positions, m (rest or current)
/// @param tets      (m) node ids; every id must be in [0, n)
/// @return          (m) qualities in [-1, 1]
[[nodiscard]] std::vector<double> tet_qualities(std::span<const Vec3> positions,
                                                std::span<const Tet> tets);

/// tet_qualities over the mesh's rest positions.
[[nodiscard]] std::vector<double> tet_qualities(const TetMesh& mesh);

}  // namespace serosa
