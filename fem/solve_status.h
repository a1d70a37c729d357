// SolveStatus: what a linear solve reports.
#pragma once

namespace serosa::fem {

struct SolveStatus {
  bool converged = false;  ///< reached the tolerance (direct solvers: factorization succeeded)
  bool finite = true;      ///< the solution has no NaN or Inf
  int iterations = 0;      ///< CG iterations taken (0 for a direct solve)
  double residual = 0.0;   ///< relative residual ||b - A x|| / ||b|| (0 when b = 0)
  /// phi(x) = x^T A x / 2 - b^T x, the quadratic A x = b minimizes (phi(0) = 0). CG decreases it
  /// monotonically, so phi > 0 means the result is worse than no update at all: diverged.
  double energy = 0.0;
};

}  // namespace serosa::fem
