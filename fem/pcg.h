// Preconditioned conjugate gradient (Saad, "Iterative Methods for Sparse Linear Systems",
// Alg. 9.1), OpenMP-parallel, on any symmetric operator y = A x (assembled CsrMatrix or the
// matrix-free system of fem/system_matrix.h), with a pluggable preconditioner z = P^{-1} r.
//   r = b - A x;  z = P^{-1} r;  p = z
//   loop: alpha = (r.z) / (p.A p);  x += alpha p;  r -= alpha A p;  stop if ||r|| <= tol ||b||
//         z = P^{-1} r;  beta = (r.z)_new / (r.z)_old;  p = z + beta p
// The vector updates of one iteration are fused into one pass (x, r, and for Jacobi z, with the
// dot products r.r and r.z), so an iteration opens three parallel regions: A p with p.Ap (one
// pass when the operator returns it, MatVecDot), the fused update, and the new direction. Dot
// products are summed over a fixed number of chunks in a fixed order, so the result is the same bit
// for bit for any OpenMP thread count (replays stay exact).
#pragma once

#include <functional>
#include <span>
#include <vector>

#include "fem/csr_matrix.h"
#include "fem/solve_status.h"

namespace serosa::fem {

/// y = A x; x and y: (rows), distinct.
using MatVec = std::function<void(std::span<const double> x, std::span<double> y)>;

/// y = A x, returning x . y (summed deterministically, as dot()): lets an operator fuse the
/// product p . Ap of the CG step into its own pass (fem/block_system.h multiply_blocks_dot).
using MatVecDot = std::function<double(std::span<const double> x, std::span<double> y)>;

/// z = P^{-1} r. Jacobi when `apply` is empty: z = inv_diag .* r (fused into the CG update);
/// otherwise `apply` (e.g. a CHOLMOD solve). r and z: (rows).
struct Preconditioner {
  std::span<const double> inv_diag;  ///< (rows) 1 / diag(A), for Jacobi
  std::function<void(std::span<const double> r, std::span<double> z)> apply;
};

/// Work vectors, kept between solves so that a step allocates nothing.
struct PcgScratch {
  std::vector<double> r, z, p, ap, inv_diag;  ///< (rows) each
};

/// Jacobi preconditioner of A: fills scratch.inv_diag = 1 / diag(A) (1 where diag <= 0).
[[nodiscard]] Preconditioner jacobi(const CsrMatrix& a, PcgScratch& scratch);

/// Solves A x = b for SPD A. x: (rows) initial guess in, solution out. Stops at relative
/// residual `tolerance` or after `max_iterations`; never returns NaN silently (finite = false).
/// A warm start worse than x = 0 (phi(x) > 0) is replaced by 0.
SolveStatus pcg(const MatVec& a, std::span<const double> b, std::span<double> x, double tolerance,
                int max_iterations, const Preconditioner& precond, PcgScratch& scratch);

/// Same with an operator that also returns x . A x.
SolveStatus pcg(const MatVecDot& a, std::span<const double> b, std::span<double> x,
                double tolerance, int max_iterations, const Preconditioner& precond,
                PcgScratch& scratch);

/// Same on an assembled matrix.
SolveStatus pcg(const CsrMatrix& a, std::span<const double> b, std::span<double> x,
                double tolerance, int max_iterations, const Preconditioner& precond,
                PcgScratch& scratch);

/// Deterministic parallel dot product (fixed chunking, see above).
[[nodiscard]] double dot(std::span<const double> x, std::span<const double> y);

}  // namespace serosa::fem
