#include "fem/csr_matrix.h"
#include "fem/parallel.h"

namespace serosa::fem {

void multiply(const CsrMatrix& a, std::span<const double> x, std::span<double> y) {
  const std::int32_t* rp = a.row_ptr.data();
  const std::int32_t* c = a.col.data();
  const double* v = a.val.data();
  const double* xp = x.data();
  double* yp = y.data();
#pragma omp parallel for schedule(static) if (a.rows >= kParallelMin)
  for (std::int32_t r = 0; r < a.rows; ++r) {
    double s = 0.0;
    for (std::int32_t k = rp[r]; k < rp[r + 1]; ++k) s += v[k] * xp[c[k]];
    yp[r] = s;
  }
}

}  // namespace serosa::fem
