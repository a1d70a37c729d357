#include "fem/pcg.h"

#include <array>
#include <cmath>
#include <cstddef>

#include "fem/parallel.h"

namespace serosa::fem {

double dot(std::span<const double> x, std::span<const double> y) {
  const double* xp = x.data();
  const double* yp = y.data();
  return chunked<1>(static_cast<std::ptrdiff_t>(x.size()),
                    [&](std::ptrdiff_t lo, std::ptrdiff_t hi, std::array<double, 1>& s) {
                      double acc = 0.0;
                      for (std::ptrdiff_t i = lo; i < hi; ++i) acc += xp[i] * yp[i];
                      s[0] = acc;
                    })[0];
}

Preconditioner jacobi(const CsrMatrix& a, PcgScratch& s) {
  s.inv_diag.assign(static_cast<std::size_t>(a.rows), 1.0);
#pragma omp parallel for schedule(static) if (a.rows >= kParallelMin)
  for (std::int32_t r = 0; r < a.rows; ++r)
    for (std::int32_t k = a.row_start[static_cast<std::size_t>(r)];
         k < a.row_start[static_cast<std::size_t>(r)] + a.row_nz[static_cast<std::size_t>(r)]; ++k)
      if (a.col[static_cast<std::size_t>(k)] == r) {
        const double d = a.val[static_cast<std::size_t>(k)];
        s.inv_diag[static_cast<std::size_t>(r)] = d > 0.0 ? 1.0 / d : 1.0;
        break;
      }
  return Preconditioner{s.inv_diag, {}};
}

SolveStatus pcg(const CsrMatrix& a, std::span<const double> b, std::span<double> x,
                double tolerance, int max_iterations, const Preconditioner& precond,
                PcgScratch& scratch) {
  return pcg([&a](std::span<const double> in, std::span<double> out) { multiply(a, in, out); }, b,
             x, tolerance, max_iterations, precond, scratch);
}

SolveStatus pcg(const MatVec& a, std::span<const double> b, std::span<double> x, double tolerance,
                int max_iterations, const Preconditioner& precond, PcgScratch& s) {
  return pcg(MatVecDot([&a](std::span<const double> in, std::span<double> out) {
               a(in, out);
               return dot(in, out);
             }),
             b, x, tolerance, max_iterations, precond, s);
}

SolveStatus pcg(const MatVecDot& a, std::span<const double> b, std::span<double> x,
                double tolerance, int max_iterations, const Preconditioner& precond,
                PcgScratch& s) {
  const auto n = static_cast<std::ptrdiff_t>(b.size());
  const auto un = static_cast<std::size_t>(n);
  s.r.resize(un);
  s.z.resize(un);
  s.p.resize(un);
  s.ap.resize(un);
  double* xp = x.data();
  const double* bp = b.data();
  double* rp = s.r.data();
  double* zp = s.z.data();
  double* pp = s.p.data();
  double* app = s.ap.data();
  const bool jac = !precond.apply;
  const double* dp = precond.inv_diag.data();
  if (jac && precond.inv_diag.size() != un) {
    SolveStatus bad;
    bad.finite = false;
    return bad;
  }
  SolveStatus st;
  const double bnorm = std::sqrt(dot(b, b));
  if (!std::isfinite(bnorm)) {
    st.finite = false;
    return st;
  }
  if (bnorm == 0.0) {  // A x = 0 has x = 0
    std::fill(x.begin(), x.end(), 0.0);
    st.converged = true;
    return st;
  }
  // phi(x) = x.(A x)/2 - b.x = -x.(b + r)/2 with r = b - A x.
  const auto phi_of = [&]() {
    return chunked<1>(n, [&](std::ptrdiff_t lo, std::ptrdiff_t hi, std::array<double, 1>& acc) {
      double v = 0.0;
      for (std::ptrdiff_t i = lo; i < hi; ++i) v -= 0.5 * xp[i] * (bp[i] + rp[i]);
      acc[0] = v;
    })[0];
  };
  // r = b - A x; a warm start worse than zero (phi > 0): start from zero.
  (void)a(x, s.r);
#pragma omp parallel for schedule(static) if (n >= kParallelMin)
  for (std::ptrdiff_t i = 0; i < n; ++i) rp[i] = bp[i] - rp[i];
  if (!(phi_of() <= 0.0)) {
    std::fill(x.begin(), x.end(), 0.0);
    std::copy(b.begin(), b.end(), s.r.begin());
  }
  // z = P^{-1} r, p = z, r.r, r.z
  if (!jac) precond.apply(s.r, s.z);
  auto sums = chunked<2>(n, [&](std::ptrdiff_t lo, std::ptrdiff_t hi, std::array<double, 2>& acc) {
    double rr = 0.0, rz = 0.0;
    for (std::ptrdiff_t i = lo; i < hi; ++i) {
      if (jac) zp[i] = dp[i] * rp[i];
      pp[i] = zp[i];
      rr += rp[i] * rp[i];
      rz += rp[i] * zp[i];
    }
    acc = {rr, rz};
  });
  double rnorm = std::sqrt(sums[0]);
  double rz = sums[1];
  int it = 0;
  while (rnorm > tolerance * bnorm && it < max_iterations) {
    const double pap = a(s.p, s.ap);
    if (!(pap > 0.0)) break;  // A not SPD along p (or NaN): stop, report unconverged
    const double alpha = rz / pap;
    // x += alpha p; r -= alpha A p; Jacobi: z = D^{-1} r; sums r.r, r.z
    sums = chunked<2>(n, [&](std::ptrdiff_t lo, std::ptrdiff_t hi, std::array<double, 2>& acc) {
      double rr = 0.0, rzl = 0.0;
      for (std::ptrdiff_t i = lo; i < hi; ++i) {
        xp[i] += alpha * pp[i];
        rp[i] -= alpha * app[i];
        rr += rp[i] * rp[i];
        if (jac) {
          zp[i] = dp[i] * rp[i];
          rzl += rp[i] * zp[i];
        }
      }
      acc = {rr, rzl};
    });
    rnorm = std::sqrt(sums[0]);
    ++it;
    if (!std::isfinite(rnorm)) break;
    if (rnorm <= tolerance * bnorm || it >= max_iterations) break;
    double rz_new = sums[1];
    if (!jac) {
      precond.apply(s.r, s.z);
      rz_new = dot(s.r, s.z);
    }
    const double beta = rz_new / rz;
    rz = rz_new;
#pragma omp parallel for schedule(static) if (n >= kParallelMin)
    for (std::ptrdiff_t i = 0; i < n; ++i) pp[i] = zp[i] + beta * pp[i];
  }
  st.iterations = it;
  st.residual = rnorm / bnorm;
  st.energy = phi_of();
  st.finite = std::isfinite(rnorm) && std::isfinite(st.energy);
  st.converged = st.finite && rnorm <= tolerance * bnorm;
  return st;
}

}  // namespace serosa::fem
