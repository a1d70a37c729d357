// The system matrix A of fem/system_matrix.h in 3x3 block storage, for CG (the CSR form stays for
// CHOLMOD). Same pattern, same storage index space: node a's blocks, one per neighbour b in its
// sorted neighbour list (pattern.nbr, position k), sit at
//   9 * nbr.start[a] + 9 k,  column-major (entry (3a+i, 3b+j) at + i + 3 j: the SpMV takes
//   rows 0-1 of a column as one SSE2 pair),
// where the CSR keeps the same 9 * count values as three rows. Against the CSR this
//  * reads one neighbour id per block in the SpMV (the CSR's col array: one int per entry),
//  * fills each node's blocks in a small scratch (L1) in double and writes them once (the CSR fill
//    zeroes the rows, then adds into them scattered over 3 rows),
//  * can hold float values (T = float): half the memory traffic of the SpMV, which is bound by
//    it. Sums stay in double (the scratch of the fill, the accumulators of the SpMV); only the
//    stored entries are rounded (relative 6e-8), see docs/BENCHMARKS.md "FEM" for the effect on
//    the solution.
// Constrained nodes (fixed, massless) get the identity times their diagonal, as in fill_system().
#pragma once

#include <array>
#include <cstdint>
#include <span>
#include <vector>

#include "engine/tet_mesh.h"
#include "fem/csr_matrix.h"
#include "fem/fem_elements.h"
#include "fem/system_matrix.h"

namespace serosa::fem {

/// Values needed by a block matrix of `pattern` (= the CSR storage size): 9 * nbr.data.size().
[[nodiscard]] std::size_t block_storage(const SystemPattern& pattern);

/// Per-tet stiffness scales of the fill: (dt^2 + dt beta_e) V_e (lambda_e, mu_e), N s^2 / m
/// (0 for inactive tets). Kept apart from the 160-byte TetElement so that the fill, which visits
/// tets in node order (scattered on unstructured meshes), reads 16 bytes per tet instead.
using TetScale = std::array<double, 2>;

/// The scale of one element for time step dt_s.
[[nodiscard]] inline TetScale tet_scale(const TetElement& e, double dt_s) {
  if (!e.active()) return {0.0, 0.0};
  const double s = (dt_s * dt_s + dt_s * e.beta_s) * e.volume_m3;
  return {s * e.lambda_pa, s * e.mu_pa};
}

/// Fills the blocks (block_storage() values; gaps left untouched) of
/// A = M + dt C + dt^2 K_R from the rotated gradients rg (4m, rotated_gradients()) and the tet
/// scales (m, tet_scale() with the same dt_s). scratch: the caller's, kept between calls (one
/// node's row per thread; grown only when the pattern's widest row grows). rows: (n) when not
/// empty, only the block rows of the nodes with rows[i] != 0 are filled (the others keep their
/// values): a node's row sums only the tets around it, so those rows are exact.
template <class T>
void fill_blocks(const TetMesh& mesh, const FemElements& el, const SystemPattern& pattern,
                 std::span<const Vec3> rg, std::span<const TetScale> scale, double dt_s,
                 std::span<T> blocks, std::vector<double>& scratch,
                 std::span<const std::uint8_t> rows = {});

/// y = A x (x, y: (3n), distinct), accumulated in double, parallel over nodes; returns x . y,
/// summed over fixed node chunks (fem/parallel.h chunked: the same bits for any thread count) in
/// the same pass: CG's p . Ap (fem/pcg.h).
template <class T>
[[nodiscard]] double multiply_blocks_dot(const SystemPattern& pattern, std::span<const T> blocks,
                                         std::span<const double> x, std::span<double> y);

/// inv_diag (3n) = 1 / diag(A) (1 where diag <= 0), the Jacobi preconditioner.
template <class T>
void blocks_inverse_diagonal(const SystemPattern& pattern, std::span<const T> blocks,
                             std::span<double> inv_diag);

/// Copies the blocks into the CSR values of `a` (built on the same pattern), for CHOLMOD-side
/// consumers and tests. rows: as fill_blocks'.
template <class T>
void blocks_to_csr(const SystemPattern& pattern, std::span<const T> blocks, CsrMatrix& a,
                   std::span<const std::uint8_t> rows = {});

}  // namespace serosa::fem
