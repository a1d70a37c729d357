// TetMesh: the organ's tetrahedral mesh as a structure of arrays (docs/ARCHITECTURE.md
// "Data model").
#pragma once

#include <cstdint>
#include <vector>

#include "engine/math.h"

namespace serosa {

/// A tetrahedral mesh. Node arrays have one entry per node (n), tet arrays one per tet (m).
/// Only cutting changes the topology, between solver steps; it bumps topology_version every time.
struct TetMesh {
  // ---- per node (n) ----
  std::vector<Vec3> rest;           ///< (n) material (rest) positions, m
  std::vector<Vec3> x;              ///< (n) current positions, m
  std::vector<Vec3> v;              ///< (n) velocities, m/s
  std::vector<double> mass;         ///< (n) lumped mass, kg (0 until FEM assigns it)
  std::vector<std::uint8_t> fixed;  ///< (n) 1 = Dirichlet node (held at its position), else 0
  // ---- per tet (m) ----
  std::vector<Tet> tets;             ///< (m) node ids, positive orientation in rest space
  std::vector<std::uint16_t> group;  ///< (m) visual mesh (Gmsh physical tag) of each tet
  /// Incremented on every topology change (tets or nodes added or removed).
  std::uint64_t topology_version = 0;

  [[nodiscard]] std::int32_t num_nodes() const { return static_cast<std::int32_t>(rest.size()); }
  [[nodiscard]] std::int32_t num_tets() const { return static_cast<std::int32_t>(tets.size()); }

  /// Appends a node at rest position p (x = p, v = 0, mass 0, free); returns its id.
  std::int32_t add_node(const Vec3& p);
  /// Appends a tet; returns its id. Does not bump topology_version (callers building a mesh
  /// from scratch do not need it; apply(TopologyDelta) does).
  std::int32_t add_tet(const Tet& t, std::uint16_t g);
  /// Resizes x, v, mass and fixed to match rest (x = rest, v = 0 for new entries).
  void fill_node_state();
  /// Signed rest volume of tet i, m^3.
  [[nodiscard]] double rest_volume(std::int32_t i) const;
};

}  // namespace serosa
