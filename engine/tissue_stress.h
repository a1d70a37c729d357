// Tissue stress and elastic node forces for metrics and tool reaction forces, computed from the
// mesh alone (no FEM internals): per tet, F = Ds Dm^-1 (current over rest edge matrices), Green
// strain E = (F^T F - I) / 2, St. Venant-Kirchhoff second Piola-Kirchhoff stress
// S = 2 mu E + lambda tr(E) I (equal to linear elasticity for small strain, and rotation
// invariant like the corotational model), and node forces f = -V0 F S Dm^-T.
#pragma once

#include <cstdint>
#include <map>
#include <span>
#include <vector>

#include "engine/math.h"
#include "engine/scene/scene.h"
#include "engine/tet_mesh.h"

namespace serosa {

/// Lamé parameters, Pa.
struct Lame {
  double mu = 0.0;
  double lambda = 0.0;
};
[[nodiscard]] Lame lame(const Material& m);

/// Group id -> Lamé parameters; groups not listed use `fallback`.
struct LameTable {
  std::map<std::uint16_t, Lame> groups;
  Lame fallback;
  [[nodiscard]] const Lame& of(std::uint16_t g) const {
    const auto it = groups.find(g);
    return it == groups.end() ? fallback : it->second;
  }
};

/// Von Mises equivalent of tet t's second Piola-Kirchhoff stress, Pa (0 for a degenerate tet).
[[nodiscard]] double von_mises_pa(const TetMesh& mesh, std::int32_t t, const Lame& lame);

/// What each tet's stress needs from its rest shape, which changes only with the topology: kept
/// across steps, the peak stress costs one 3x3 product per tet instead of an inverse and a table
/// look-up.
struct RestStress {
  std::vector<Mat3> dm_inv;      ///< (m) inverse rest edge matrices, 1/m
  std::vector<Lame> lame;        ///< (m) the tet's Lamé parameters, Pa
  std::vector<std::uint8_t> ok;  ///< (m) 0 for a degenerate rest tet (stress 0)
};

/// Fills `rest` for the mesh's current topology (reusing its memory).
void fill_rest_stress(const TetMesh& mesh, const LameTable& table, RestStress& rest);

/// Largest von Mises stress over all tets, Pa, given the rest data of the mesh's current
/// topology: the same bits as the largest von_mises_pa.
[[nodiscard]] double peak_von_mises_pa(const TetMesh& mesh, const RestStress& rest);

/// Adds to f (n) the elastic forces on the nodes flagged in `wanted` (n, nonzero = wanted), N,
/// from every tet touching one of them.
void add_elastic_forces(const TetMesh& mesh, const LameTable& table,
                        std::span<const std::uint8_t> wanted, std::vector<Vec3>& f);

}  // namespace serosa
