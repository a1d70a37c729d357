// CsrMatrix: a square sparse matrix in compressed sparse row form, the storage the implicit step
// assembles into (pattern once per topology version, values every step) and both solvers read.
// For the symmetric system matrices used here the row arrays are also a valid compressed-column
// view, which is how CHOLMOD reads them without a copy.
#pragma once

#include <cstdint>
#include <span>
#include <vector>

namespace serosa::fem {

struct CsrMatrix {
  std::int32_t rows = 0;              ///< number of rows = columns (3n for n nodes)
  std::vector<std::int32_t> row_ptr;  ///< (rows + 1) start of each row in col/val
  std::vector<std::int32_t> col;      ///< (nnz) column of each entry, ascending within a row
  std::vector<double> val;            ///< (nnz) value of each entry

  [[nodiscard]] std::int64_t nnz() const { return static_cast<std::int64_t>(col.size()); }
};

/// y = A x, parallel over rows (OpenMP). x and y: (rows), distinct.
void multiply(const CsrMatrix& a, std::span<const double> x, std::span<double> y);

}  // namespace serosa::fem
