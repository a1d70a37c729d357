// Operations on CsrMatrix (engine/csr_matrix.h): packed copies and products.
#pragma once

#include <cstdint>
#include <span>
#include <vector>

#include "engine/csr_matrix.h"

namespace serosa::fem {

using serosa::CsrMatrix;

/// to = from with its rows packed (no slack). to's buffers are reused, and grown with a quarter to
/// spare when they must grow, so that copying a matrix that grows a little after each cut touches
/// no fresh memory most of the time.
void copy_packed(const CsrMatrix& from, CsrMatrix& to);

/// y = A x, parallel over rows (OpenMP). x and y: (rows), distinct.
void multiply(const CsrMatrix& a, std::span<const double> x, std::span<double> y);

}  // namespace serosa::fem
