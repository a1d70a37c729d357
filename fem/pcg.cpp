#include "fem/pcg.h"
#include "fem/parallel.h"

#include <array>
#include <cmath>

namespace serosa::fem {
namespace {

constexpr int kChunks = 64;  // fixed: makes dot() independent of the thread count

void axpy(double alpha, std::span<const double> x, std::span<double> y) {
  const auto n = static_cast<std::ptrdiff_t>(y.size());
#pragma omp parallel for schedule(static) if (n >= kParallelMin)
  for (std::ptrdiff_t i = 0; i < n; ++i)
    y[static_cast<std::size_t>(i)] += alpha * x[static_cast<std::size_t>(i)];
}

}  // namespace

double dot(std::span<const double> x, std::span<const double> y) {
  const auto n = static_cast<std::ptrdiff_t>(x.size());
  std::array<double, kChunks> part{};
#pragma omp parallel for schedule(static) if (n >= kParallelMin)
  for (int c = 0; c < kChunks; ++c) {
    const std::ptrdiff_t lo = n * c / kChunks;
    const std::ptrdiff_t hi = n * (c + 1) / kChunks;
    double s = 0.0;
    for (std::ptrdiff_t i = lo; i < hi; ++i)
      s += x[static_cast<std::size_t>(i)] * y[static_cast<std::size_t>(i)];
    part[static_cast<std::size_t>(c)] = s;
  }
  double s = 0.0;
  for (double v : part) s += v;
  return s;
}

Preconditioner jacobi(const CsrMatrix& a, PcgScratch& s) {
  s.inv_diag.assign(static_cast<std::size_t>(a.rows), 1.0);
#pragma omp parallel for schedule(static) if (a.rows >= kParallelMin)
  for (std::int32_t r = 0; r < a.rows; ++r)
    for (std::int32_t k = a.row_ptr[static_cast<std::size_t>(r)];
         k < a.row_ptr[static_cast<std::size_t>(r) + 1]; ++k)
      if (a.col[static_cast<std::size_t>(k)] == r) {
        const double d = a.val[static_cast<std::size_t>(k)];
        s.inv_diag[static_cast<std::size_t>(r)] = d > 0.0 ? 1.0 / d : 1.0;
        break;
      }
  return [&s](std::span<const double> r, std::span<double> z) {
    const auto n = static_cast<std::ptrdiff_t>(r.size());
#pragma omp parallel for schedule(static) if (n >= kParallelMin)
    for (std::ptrdiff_t i = 0; i < n; ++i)
      z[static_cast<std::size_t>(i)] =
          s.inv_diag[static_cast<std::size_t>(i)] * r[static_cast<std::size_t>(i)];
  };
}

SolveStatus pcg(const CsrMatrix& a, std::span<const double> b, std::span<double> x,
                double tolerance, int max_iterations, const Preconditioner& precond,
                PcgScratch& s) {
  const auto n = static_cast<std::size_t>(a.rows);
  s.r.resize(n);
  s.z.resize(n);
  s.p.resize(n);
  s.ap.resize(n);
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
  // r = b - A x
  multiply(a, x, s.r);
#pragma omp parallel for schedule(static) if (static_cast <std::ptrdiff_t>(n) >= kParallelMin)
  for (std::ptrdiff_t i = 0; i < static_cast<std::ptrdiff_t>(n); ++i)
    s.r[static_cast<std::size_t>(i)] =
        b[static_cast<std::size_t>(i)] - s.r[static_cast<std::size_t>(i)];
  double rnorm = std::sqrt(dot(s.r, s.r));
  // phi(x0) = -x0.(b + r0) / 2; a warm start worse than zero (phi > 0): start from zero.
  double phi0 = 0.0;
  for (std::size_t i = 0; i < n; ++i) phi0 -= 0.5 * x[i] * (b[i] + s.r[i]);
  if (!(phi0 <= 0.0)) {
    std::fill(x.begin(), x.end(), 0.0);
    std::copy(b.begin(), b.end(), s.r.begin());
    rnorm = bnorm;
  }
  precond(s.r, s.z);
  std::copy(s.z.begin(), s.z.end(), s.p.begin());
  double rz = dot(s.r, s.z);
  int it = 0;
  while (rnorm > tolerance * bnorm && it < max_iterations) {
    multiply(a, s.p, s.ap);
    const double pap = dot(s.p, s.ap);
    if (!(pap > 0.0)) break;  // A not SPD along p (or NaN): stop, report unconverged
    const double alpha = rz / pap;
    axpy(alpha, s.p, x);
    axpy(-alpha, s.ap, s.r);
    rnorm = std::sqrt(dot(s.r, s.r));
    ++it;
    if (!std::isfinite(rnorm)) break;
    if (rnorm <= tolerance * bnorm) break;
    precond(s.r, s.z);
    const double rz_new = dot(s.r, s.z);
    const double beta = rz_new / rz;
    rz = rz_new;
#pragma omp parallel for schedule(static) if (static_cast <std::ptrdiff_t>(n) >= kParallelMin)
    for (std::ptrdiff_t i = 0; i < static_cast<std::ptrdiff_t>(n); ++i)
      s.p[static_cast<std::size_t>(i)] =
          s.z[static_cast<std::size_t>(i)] + beta * s.p[static_cast<std::size_t>(i)];
  }
  st.iterations = it;
  st.residual = rnorm / bnorm;
  // phi(x) = x.(A x)/2 - b.x = -x.(b + r)/2 with r = b - A x (r is the recurrence residual).
  double phi = 0.0;
  for (std::size_t i = 0; i < n; ++i) phi -= 0.5 * x[i] * (b[i] + s.r[i]);
  st.energy = phi;
  st.finite = std::isfinite(rnorm) && std::isfinite(phi);
  st.converged = st.finite && rnorm <= tolerance * bnorm;
  return st;
}

}  // namespace serosa::fem
