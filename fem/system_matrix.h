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
