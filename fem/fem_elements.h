// FemElements: everything FEM precomputes from the rest mesh (per-tet elements, lumped node masses)
// for one topology version. Built in full once, then updated from each TopologyDelta touching only
// the removed and added tets and their nodes (engine/topology_delta.h apply() slot rules).
#pragma once

#include <cstdint>
#include <vector>

#include "engine/tet_mesh.h"
#include "engine/topology_delta.h"
#include "fem/fem_config.h"
#include "fem/tet_element.h"

namespace serosa::fem {

struct FemElements {
  std::vector<TetElement> elements;  ///< (m) one per tet, same ids as TetMesh::tets
  std::vector<double> node_mass;     ///< (n) lumped mass m_i = sum_e rho_e V_e / 4, kg
  std::vector<double>
      node_damping;  ///< (n) lumped alpha M: c_i = sum_e alpha_e rho_e V_e / 4, kg/s
  std::uint64_t topology_version = 0;  ///< TetMesh::topology_version these were built for
  std::int64_t debris_tets = 0;        ///< tets of debris pieces, left inactive (below)
  double debris_volume_m3 = 0.0;       ///< their rest volume, m^3
};

/// A piece of tissue whose rest volume is below this, m^3 (0.1 mm^3, a chip half a millimetre
/// across), connected to nothing else, is debris: the chips two nearly coincident cuts leave
/// between them, a few slivers weighing micrograms. FEM leaves its elements inactive (no mass, no
/// stiffness: its nodes stay where they were cut), since no solver tolerance that suits the organs
/// converges such a piece, and an unconverged one gains energy step after step until it flies off.
inline constexpr double kDebrisVolumeM3 = 1e-10;

/// Full precompute for `mesh` (rest positions, tets, groups); debris pieces inactive.
void build_elements(const TetMesh& mesh, const FemConfig& config, FemElements& out);

/// Incremental update after `apply(mesh, delta)`: `mesh` is the mesh after the change and `delta`
/// has its apply() outputs filled. Requires out.topology_version == delta.version_before.
/// Recomputes only the added elements and the masses of their nodes and of the removed tets'
/// nodes, and looks for debris again. Equals build_elements() on the new mesh up to round-off in
/// the node sums.
void update_elements(const TetMesh& mesh, const TopologyDelta& delta, const FemConfig& config,
                     FemElements& out);

}  // namespace serosa::fem
