// CholmodSolver: sparse Cholesky A = L L^T through SuiteSparse CHOLMOD (supernodal when it pays).
// Precompute/solve split: analyze() (fill-reducing ordering, symbolic factorization) once per
// sparsity pattern, i.e. once per topology version; factorize() (numeric) whenever the values
// change; solve() any number of times. Reads the CsrMatrix in place as the upper triangle of a
// symmetric compressed-column matrix (the CSR of a symmetric matrix is its CSC). cholmod.h stays
// out of this header.
#pragma once

#include <cstdint>
#include <memory>
#include <span>

#include "fem/block_factor.h"
#include "fem/csr_matrix.h"
#include "fem/solve_status.h"

namespace serosa::fem {

class CholmodSolver {
 public:
  /// How CHOLMOD lays out the factor: its own choice (supernodal when the fill pays for dense
  /// blocks), or simplicial (column by column, no BLAS): on meshes of a few thousand nodes its
  /// triangular solves are cheaper, which is what a preconditioner applied every CG iteration
  /// needs (docs/BENCHMARKS.md "FEM").
  /// node_blocks: supernodal L L^T under an ordering of the node graph (AMD), so that each
  /// node's three rows stay together and the factor can be exported as 3x3 blocks of an LDL^T
  /// (export_ldl, fem/block_factor.h), whose solves replace CHOLMOD's. Supernodal because its
  /// numeric factorization, the lagged factor's background refresh, runs in dense blocks through
  /// BLAS: a fifth of the simplicial time with OpenBLAS at the default scene's size, about half
  /// with the reference BLAS (docs/BENCHMARKS.md "Factor layout").
  enum class Layout : std::uint8_t { automatic, simplicial, node_blocks };

  explicit CholmodSolver(Layout layout = Layout::automatic);
  ~CholmodSolver();
  CholmodSolver(const CholmodSolver&) = delete;
  CholmodSolver& operator=(const CholmodSolver&) = delete;

  /// Symbolic analysis of a's pattern (values ignored). Returns false if CHOLMOD fails.
  bool analyze(const CsrMatrix& a);
  /// Numeric factorization of a (same pattern as analyzed). False if a is not positive definite.
  [[nodiscard]] bool factorize(const CsrMatrix& a);
  /// The analysis of `from` (analyzed, of the same pattern) instead of analyze(): a copy of its
  /// factor, whose values the next factorize() overwrites. Only reads `from`.
  bool copy_analysis(const CholmodSolver& from);
  /// x = A^{-1} b with the last factorization; b and x: (rows). Status: converged = factor ok.
  SolveStatus solve(std::span<const double> b, std::span<double> x);

  /// The factor as plain arrays of an LDL^T (fem/block_factor.h LdlFactor; a supernodal L L^T is
  /// scaled to it, and its exact zeros, the padding of relaxed supernodes, left out); false
  /// unless the layout is simplicial or node_blocks and a factorization succeeded.
  bool export_ldl(LdlFactor& out) const;

  [[nodiscard]] bool analyzed() const;
  [[nodiscard]] bool factorized() const;

 private:
  struct Impl;
  std::unique_ptr<Impl> m_impl;
};

}  // namespace serosa::fem
