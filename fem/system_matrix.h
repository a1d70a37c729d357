// System matrix of the implicit step, A = (M + dt alpha M) + (dt^2 + dt beta) R K R^T, assembled
// into a CsrMatrix. Split precompute/fill (libigl's min_quad_with_fixed):
//  * build_pattern(): once. Node a's three rows hold the columns 3b..3b+2 of every node b sharing
//    a tet with a (sorted, a itself included), so entry (3a+i, 3b+j) sits at
//      block_start + i * row_len(a) + j,
//    and every (tet, a, b) block start is precomputed. Also builds node -> (tet, corner) incidence.
//  * update_pattern(): after a topology change (engine/topology_delta.h), local. Only the nodes of
//    removed and added tets get a new incidence and neighbour list; a node whose neighbour list
//    changed rewrites its three rows in place when they fit its capacity, else moves them to the
//    end of the storage with 50% slack (the CSR is unpacked: row_start/row_nz, so no other row
//    moves); only the tets touching such a node, and the added and relabelled tets, recompute
//    their block starts. Entries of neighbours a node no longer shares a tet with are dropped.
//    When moved rows leave gaps over half the storage in use, it is compacted (amortized).
//    The result holds exactly the entries of a full build_pattern() on the new mesh, in the same
//    order within each row, with the same incidence order (ascending tet), so fill_system()
//    gives the same values bit for bit.
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
#include "engine/topology_delta.h"
#include "fem/csr_matrix.h"
#include "fem/fem_elements.h"

namespace serosa::fem {

/// A list per node kept in one flat array with room to grow: node i's items are
/// data[start[i] .. start[i] + count[i]), with capacity cap[i] >= count[i].
struct SlackLists {
  std::vector<std::int32_t> start;  ///< (n) first item of each list in data
  std::vector<std::int32_t> count;  ///< (n) items in use
  std::vector<std::int32_t> cap;    ///< (n) items reserved
  std::vector<std::int32_t> data;   ///< (storage) items, with unused gaps
  std::int64_t used = 0;            ///< sum of cap (storage in live lists)

  [[nodiscard]] std::span<const std::int32_t> of(std::size_t i) const {
    return {data.data() + start[i], static_cast<std::size_t>(count[i])};
  }
};

struct SystemPattern {
  std::int32_t nodes = 0;
  /// Node i's neighbour list (sorted node ids sharing a tet with i, i included). Its three rows
  /// use the value/column storage from 9 * nbr.start[i] (capacity 9 * nbr.cap[i]).
  SlackLists nbr;
  std::vector<std::int32_t> row_len;                ///< (n) entries per row of node a = 3 deg
  std::vector<std::int32_t> diag_start;             ///< (n) index of entry (3a, 3a)
  std::vector<std::array<std::int32_t, 16>> block;  ///< (m x 4 x 4) index of (3 t_a, 3 t_b)
  /// Node i's incident corners 4 * tet + corner, ascending.
  SlackLists incident;
  std::uint64_t topology_version = 0;

  [[nodiscard]] std::span<const std::int32_t> incident_of(std::size_t i) const {
    return incident.of(i);
  }
};

/// What update_pattern() touched (for tests and benchmarks).
struct PatternUpdateStats {
  std::int32_t nodes_touched = 0;   ///< nodes whose incidence was recomputed
  std::int32_t rows_rewritten = 0;  ///< nodes whose neighbour list (three rows) changed
  std::int32_t rows_moved = 0;      ///< of those, moved to the end of the storage
  std::int32_t blocks_updated = 0;  ///< tets whose block starts were recomputed
  bool compacted = false;           ///< the storage was compacted
};

/// Builds the pattern and the matrix structure (values zeroed) for the mesh's tets.
void build_pattern(const TetMesh& mesh, SystemPattern& pattern, CsrMatrix& a);

/// Local update after `apply(mesh, delta)` (mesh: after the change; delta: with its apply()
/// outputs). removed: (r) node ids of the removed tets, in delta.removed_tets order (the mesh no
/// longer has them). Requires pattern.topology_version == delta.version_before. Values of
/// rewritten rows are zero; the others are left as they were.
PatternUpdateStats update_pattern(const TetMesh& mesh, const TopologyDelta& delta,
                                  std::span<const Tet> removed, SystemPattern& pattern,
                                  CsrMatrix& a);

/// True where node i takes no part in the solve (fixed, or no mass): dv_i = 0.
[[nodiscard]] inline bool node_constrained(const TetMesh& mesh, const FemElements& el,
                                           std::size_t i) {
  return mesh.fixed[i] != 0 || !(el.node_mass[i] > 0.0);
}

/// Rotated shape-function gradients rg (4m): rg[4e + a] = R_e b_a (1/m), what both the assembled
/// and the matrix-free system need: R K_ab R^T = V (lambda ra rb^T + mu rb ra^T + mu (ra.rb) I).
/// rot: (m); identity rotations give the rest-state (linear) system.
void rotated_gradients(const FemElements& el, std::span<const Mat3> rot, std::span<Vec3> rg);

/// Fills A's values: A = M + dt C + dt^2 K_R with C = alpha M + beta K_R, K_R = R K R^T, from the
/// rotated gradients rg (4m, rotated_gradients()).
void fill_system(const TetMesh& mesh, const FemElements& el, const SystemPattern& pattern,
                 std::span<const Vec3> rg, double dt_s, CsrMatrix& a);

/// y = A x for a matrix built by build_pattern() (x, y: (3n)). Exploits its layout: a node's three
/// rows share their columns, which come in triples, so one column index is read per 3x3 block
/// (a blocked SpMV on the CSR arrays CHOLMOD reads). Parallel over nodes.
void multiply_system(const SystemPattern& pattern, const CsrMatrix& a, std::span<const double> x,
                     std::span<double> y);

/// The same A without assembling it (matrix-free):
///   A x = D x + sum_e s_e R_e K_e R_e^T x,  D = diag(m_i + dt c_i),  s_e = dt^2 + dt beta_e,
/// evaluated per tet through the stress like the elastic forces: with H_e = sum_b x_b rb^T,
/// (K_R x)_a = V sigma(sym H_e) ra. Two passes, both conflict-free in parallel: per tet its four
/// corner forces, then per node the sum over its incident corners (pattern.incident). Rows and
/// columns of constrained nodes are the identity times their diagonal, as in fill_system().
struct SystemOperator {
  std::vector<double> diag;        ///< (n) D_i (constrained: m_i, or 1 if massless)
  std::vector<std::uint8_t> free;  ///< (n) 1 where the node takes part in the solve
  std::vector<double> tet_scale;   ///< (m) (dt^2 + dt beta_e) V_e, s^2 m^3 (0: inactive)
  std::vector<Vec3> corner;        ///< (4m) scratch: s_e (K_R,e x)_a per corner
};

/// Per-step data of the operator (masses, constraints, scales) for time step dt_s.
void prepare_operator(const TetMesh& mesh, const FemElements& el, double dt_s, SystemOperator& op);

/// y = A x, matrix-free. rg: (4m) rotated gradients; x, y: (3n).
void apply_operator(const TetMesh& mesh, const FemElements& el, const SystemPattern& pattern,
                    std::span<const Vec3> rg, SystemOperator& op, std::span<const double> x,
                    std::span<double> y);

/// inv_diag (3n) = 1 / diag(A) of the matrix-free operator (Jacobi preconditioner).
void operator_inverse_diagonal(const FemElements& el, const SystemPattern& pattern,
                               std::span<const Vec3> rg, const SystemOperator& op,
                               std::span<double> inv_diag);

}  // namespace serosa::fem
