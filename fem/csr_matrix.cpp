#include "fem/csr_matrix.h"

#include <algorithm>
#include "fem/parallel.h"

namespace serosa::fem {

namespace {
template <class T>
void resize_with_room(std::vector<T>& v, std::size_t n) {
  if (v.capacity() < n) {
    v.clear();
    v.reserve(n + n / 4);
  }
  v.resize(n);
}
}  // namespace

void copy_packed(const CsrMatrix& from, CsrMatrix& to) {
  const auto rows = static_cast<std::size_t>(from.rows);
  to.rows = from.rows;
  resize_with_room(to.row_start, rows + 1);
  resize_with_room(to.row_nz, rows);
  resize_with_room(to.col, static_cast<std::size_t>(from.nnz()));
  resize_with_room(to.val, to.col.size());
  std::int32_t at = 0;
  for (std::size_t r = 0; r < rows; ++r) {
    const std::int32_t n = from.row_nz[r];
    const auto begin = static_cast<std::size_t>(from.row_start[r]);
    to.row_start[r] = at;
    to.row_nz[r] = n;
    std::copy_n(from.col.begin() + static_cast<std::ptrdiff_t>(begin), n, to.col.begin() + at);
    std::copy_n(from.val.begin() + static_cast<std::ptrdiff_t>(begin), n, to.val.begin() + at);
    at += n;
  }
  to.row_start[rows] = at;
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
