#include "fem/csr_matrix.h"
#include "fem/parallel.h"

namespace serosa::fem {

std::int64_t CsrMatrix::nnz() const {
  std::int64_t s = 0;
  for (std::int32_t n : row_nz) s += n;
  return s;
}

void multiply(const CsrMatrix& a, std::span<const double> x, std::span<double> y) {
  const std::int32_t* rs = a.row_start.data();
  const std::int32_t* rn = a.row_nz.data();
  const std::int32_t* c = a.col.data();
  const double* v = a.val.data();
  const double* xp = x.data();
  double* yp = y.data();
#pragma omp parallel for schedule(static) if (a.rows >= kParallelMin)
  for (std::int32_t r = 0; r < a.rows; ++r) {
    double s = 0.0;
    for (std::int32_t k = rs[r]; k < rs[r] + rn[r]; ++k) s += v[k] * xp[c[k]];
    yp[r] = s;
  }
}

}  // namespace serosa::fem
