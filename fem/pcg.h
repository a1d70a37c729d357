// Preconditioned conjugate gradient on a CsrMatrix (Saad, "Iterative Methods for Sparse Linear
// Systems", Alg. 9.1), OpenMP-parallel, with a pluggable preconditioner z = P^{-1} r.
//   r = b - A x;  z = P^{-1} r;  p = z
//   loop: alpha = (r.z) / (p.A p);  x += alpha p;  r -= alpha A p;  stop if ||r|| <= tol ||b||
//         z = P^{-1} r;  beta = (r.z)_new / (r.z)_old;  p = z + beta p
// Dot products are summed over a fixed number of chunks in a fixed order, so the result is the
// same bit for bit for any OpenMP thread count (replays stay exact).
#pragma once

#include <functional>
#include <span>
#include <vector>

#include "fem/csr_matrix.h"
#include "fem/solve_status.h"

namespace serosa::fem {

/// z = P^{-1} r; r and z: (rows).
using Preconditioner = std::function<void(std::span<const double> r, std::span<double> z)>;

/// Work vectors, kept between solves so that a step allocates nothing.
struct PcgScratch {
  std::vector<double> r, z, p, ap, inv_diag;  ///< (rows) each
};

/// Jacobi preconditioner of A: fills scratch.inv_diag = 1 / diag(A) and returns P^{-1} r =
/// inv_diag .* r (reads scratch, which must outlive it).
[[nodiscard]] Preconditioner jacobi(const CsrMatrix& a, PcgScratch& scratch);

/// Solves A x = b for SPD A. x: (rows) initial guess in, solution out. Stops at relative
/// residual `tolerance` or after `max_iterations`; never returns NaN silently (finite = false).
SolveStatus pcg(const CsrMatrix& a, std::span<const double> b, std::span<double> x,
                double tolerance, int max_iterations, const Preconditioner& precond,
                PcgScratch& scratch);

/// Deterministic parallel dot product (fixed chunking, see above).
[[nodiscard]] double dot(std::span<const double> x, std::span<const double> y);

}  // namespace serosa::fem
