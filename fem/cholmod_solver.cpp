#include "fem/cholmod_solver.h"

#include <cholmod.h>

#include <algorithm>
#include <cmath>

namespace serosa::fem {

struct CholmodSolver::Impl {
  cholmod_common common{};
  cholmod_factor* factor = nullptr;
  cholmod_dense* b = nullptr;  // (rows x 1) right-hand side
  cholmod_dense* x = nullptr;  // solution workspace, reused by cholmod_solve2
  cholmod_dense* y = nullptr;
  cholmod_dense* e = nullptr;
  std::int32_t rows = 0;
  bool ok_factor = false;

  Impl() {
    cholmod_start(&common);
    common.print = 0;
    common.error_handler = nullptr;
  }
  ~Impl() {
    free_all();
    cholmod_finish(&common);
  }
  Impl(const Impl&) = delete;
  Impl& operator=(const Impl&) = delete;

  void free_all() {
    if (factor != nullptr) cholmod_free_factor(&factor, &common);
    for (cholmod_dense** d : {&b, &x, &y, &e})
      if (*d != nullptr) cholmod_free_dense(d, &common);
    ok_factor = false;
  }

  // A view of the CSR arrays as a symmetric, unpacked CSC matrix (upper triangle used). CHOLMOD
  // only reads through the pointers, so the const_casts are safe.
  static cholmod_sparse view(const CsrMatrix& a) {
    cholmod_sparse s{};
    s.nrow = static_cast<std::size_t>(a.rows);
    s.ncol = static_cast<std::size_t>(a.rows);
    s.nzmax = static_cast<std::size_t>(a.storage());
    s.p = const_cast<std::int32_t*>(a.row_start.data());
    s.nz = const_cast<std::int32_t*>(a.row_nz.data());
    s.i = const_cast<std::int32_t*>(a.col.data());
    s.x = const_cast<double*>(a.val.data());
    s.stype = 1;
    s.itype = CHOLMOD_INT;
    s.xtype = CHOLMOD_REAL;
    s.dtype = CHOLMOD_DOUBLE;
    s.sorted = 1;
    s.packed = 0;  // rows may leave slack (fem/csr_matrix.h)
    return s;
  }
};

CholmodSolver::CholmodSolver(Layout layout) : m_impl(std::make_unique<Impl>()) {
  if (layout == Layout::simplicial) m_impl->common.supernodal = CHOLMOD_SIMPLICIAL;
}
CholmodSolver::~CholmodSolver() = default;

bool CholmodSolver::analyze(const CsrMatrix& a) {
  Impl& m = *m_impl;
  m.free_all();
  m.rows = a.rows;
  cholmod_sparse s = Impl::view(a);
  m.factor = cholmod_analyze(&s, &m.common);
  if (m.factor == nullptr) return false;
  m.b = cholmod_zeros(static_cast<std::size_t>(a.rows), 1, CHOLMOD_REAL, &m.common);
  return m.b != nullptr;
}

bool CholmodSolver::factorize(const CsrMatrix& a) {
  Impl& m = *m_impl;
  m.ok_factor = false;
  if (m.factor == nullptr || a.rows != m.rows) return false;
  cholmod_sparse s = Impl::view(a);
  const int ok = cholmod_factorize(&s, m.factor, &m.common);
  m.ok_factor = ok != 0 && m.common.status == CHOLMOD_OK && m.factor->minor == m.factor->n;
  return m.ok_factor;
}

SolveStatus CholmodSolver::solve(std::span<const double> b, std::span<double> x) {
  Impl& m = *m_impl;
  SolveStatus st;
  if (!m.ok_factor) {
    st.converged = false;
    st.finite = false;
    return st;
  }
  std::copy(b.begin(), b.end(), static_cast<double*>(m.b->x));
  const int ok =
      cholmod_solve2(CHOLMOD_A, m.factor, m.b, nullptr, &m.x, nullptr, &m.y, &m.e, &m.common);
  if (ok == 0 || m.x == nullptr) {
    st.converged = false;
    st.finite = false;
    return st;
  }
  const double* xs = static_cast<const double*>(m.x->x);
  std::copy(xs, xs + m.rows, x.begin());
  st.finite = std::all_of(x.begin(), x.end(), [](double v) { return std::isfinite(v); });
  st.converged = ok != 0 && st.finite;
  return st;
}

bool CholmodSolver::analyzed() const { return m_impl->factor != nullptr; }
bool CholmodSolver::factorized() const { return m_impl->ok_factor; }

}  // namespace serosa::fem
