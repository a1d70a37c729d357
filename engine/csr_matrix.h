// CsrMatrix: a square sparse matrix in compressed sparse row form, the storage the implicit step
// assembles into (fem/csr_matrix.h: pattern once per topology version, patched locally after a
// cut; values every step) and both solvers read. Rows may be *unpacked*: row r holds row_nz[r]
// entries from row_start[r], and the storage may hold unused slack between rows (room to grow
// after a cut without moving every other row). For the symmetric system matrices used here the
// row arrays are also a valid compressed-column view (CHOLMOD's unpacked form, p = row_start,
// nz = row_nz), which is how CHOLMOD reads them without a copy. Plain data: the FEM's block of
// the state keeps the matrices its factors were computed from (engine/fem_block.h).
#pragma once

#include <cstdint>
#include <vector>

namespace serosa {

struct CsrMatrix {
  std::int32_t rows = 0;                ///< number of rows = columns (3n for n nodes)
  std::vector<std::int32_t> row_start;  ///< (rows + 1) start of each row in col/val; [rows] = size
  std::vector<std::int32_t> row_nz;     ///< (rows) entries used in each row
  std::vector<std::int32_t> col;        ///< (storage) column of each entry, ascending within a row
  std::vector<double> val;              ///< (storage) value of each entry

  /// Entries in use (sum of row_nz).
  [[nodiscard]] std::int64_t nnz() const {
    std::int64_t s = 0;
    for (std::int32_t n : row_nz) s += n;
    return s;
  }
  /// Entries allocated, slack and unused gaps included.
  [[nodiscard]] std::int64_t storage() const { return static_cast<std::int64_t>(col.size()); }
  template <class S, class F>
  static void each(S& s, F&& f) {
    f(s.rows), f(s.row_start), f(s.row_nz), f(s.col), f(s.val);
  }
};

}  // namespace serosa
