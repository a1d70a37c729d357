// BlockFactor: the triangular solves of a sparse LDL^T factor of a 3n x 3n system, stored as 3x3
// node blocks in single precision.
//
// Why: the lagged-factor preconditioner (fem/lagged_factor.h) spends most of a CG iteration in the
// two triangular solves, which stream the whole factor from memory once each. CHOLMOD's simplicial
// factor takes 12 bytes an entry (a double and an int index); as 3x3 blocks in float with one index
// a block it takes 4.4, and the block products need no index per entry. The factor is only a
// preconditioner: solving in float (the default scene's solve agrees with CHOLMOD's to about 1e-4)
// changes how fast CG converges, never what it converges to, since CG's residual is computed in
// double. Measured on the default scene (docs/BENCHMARKS.md "FEM"): one solve 0.18 ms against
// CHOLMOD's 0.27 ms, for about a tenth more CG iterations.
//
// The factor must keep each node's three rows together and in order (CholmodSolver's node-block
// layout orders the node graph, not the scalar one): build() checks it and fails otherwise, and
// the caller then keeps CHOLMOD's own solve.
#pragma once

#include <cstdint>
#include <span>
#include <vector>

namespace serosa::fem {

/// A simplicial LDL^T factor of P A P^T as plain arrays (CholmodSolver::export_ldl): L unit lower
/// triangular, column by column, its diagonal implicit.
struct LdlFactor {
  std::vector<std::int32_t> perm;       ///< (rows) row k of P A P^T is row perm[k] of A
  std::vector<std::int32_t> col_start;  ///< (rows + 1) start of each column's entries
  std::vector<std::int32_t> row;        ///< (entries) row of each strictly-lower entry
  std::vector<double> val;              ///< (entries) its value
  std::vector<double> d;                ///< (rows) D
};

class BlockFactor {
 public:
  /// Builds the block form of `f`. False (and empty) when its permutation splits a node's rows
  /// or D is not positive.
  bool build(const LdlFactor& f);
  /// x = A^{-1} b through the factor; b, x: (rows()), may alias.
  void solve(std::span<const double> b, std::span<double> x);
  [[nodiscard]] std::int32_t rows() const { return 3 * m_nodes; }
  [[nodiscard]] bool empty() const { return m_nodes == 0; }
  void clear();

 private:
  std::int32_t m_nodes = 0;
  std::vector<std::int32_t> m_node_of;      // (nodes) permuted node k is node m_node_of[k] of A
  std::vector<float> m_diag;                // (nodes x 6) l10 l20 l21 and 1/d0 1/d1 1/d2
  std::vector<std::int32_t> m_block_start;  // (nodes + 1) start of each node column's blocks
  std::vector<std::int32_t> m_block_row;    // (blocks) permuted node of each block
  std::vector<float> m_block;               // (blocks x 9) L_IJ row-major
  std::vector<float> m_y;                   // (rows) the permuted right-hand side, then solution
};

}  // namespace serosa::fem
