// System matrix of the implicit step, A = (M + dt alpha M) + (dt^2 + dt beta) R K R^T, assembled
// into a CsrMatrix. Split precompute/fill (libigl's min_quad_with_fixed):
//  * build_pattern(): once per topology version. Node a's three rows hold the columns 3b..3b+2 of
//    every node b sharing a tet with a (sorted), so entry (3a+i, 3b+j) sits at
//      block_start + i * row_len(a) + j,
//    and every (tet, a, b) block start is precomputed. Also builds node -> (tet, corner) incidence.
//  * fill_system(): every step, in parallel over nodes (each thread writes only its own rows, so no
//    atomics and the result is the same for any thread count).
// Dirichlet nodes (TetMesh::fixed) and massless nodes (no active tet) get the row and column of
// the identity scaled by their diagonal mass (1 when massless), so dv = 0 there and A stays SPD.
#pragma once

#include <array>
#include <cstdint>
#include <span>
#include <vector>

#include "engine/tet_mesh.h"
#include "fem/csr_matrix.h"
#include "fem/fem_elements.h"

namespace serosa::fem {

struct SystemPattern {
  std::int32_t nodes = 0;
  std::vector<std::int32_t> row_len;                ///< (n) entries per row of node a = 3 deg
  std::vector<std::int32_t> diag_start;             ///< (n) index of entry (3a, 3a)
  std::vector<std::array<std::int32_t, 16>> block;  ///< (m x 4 x 4) index of (3 t_a, 3 t_b)
  std::vector<std::int32_t> incident_ptr;           ///< (n + 1) start in incident
  std::vector<std::int32_t> incident;               ///< (4m) 4 * tet + corner, by node
  std::uint64_t topology_version = 0;
};

/// Builds the pattern and the matrix structure (values zeroed) for the mesh's tets.
void build_pattern(const TetMesh& mesh, SystemPattern& pattern, CsrMatrix& a);

/// True where node i takes no part in the solve (fixed, or no mass): dv_i = 0.
[[nodiscard]] inline bool node_constrained(const TetMesh& mesh, const FemElements& el,
                                           std::size_t i) {
  return mesh.fixed[i] != 0 || !(el.node_mass[i] > 0.0);
}

/// Fills A's values: A = M + dt C + dt^2 K_R with C = alpha M + beta K_R, K_R = R K R^T.
/// rot: (m) per-tet rotation R (identity gives the linear, rest-state system).
void fill_system(const TetMesh& mesh, const FemElements& el, const SystemPattern& pattern,
                 std::span<const Mat3> rot, double dt_s, CsrMatrix& a);

}  // namespace serosa::fem
