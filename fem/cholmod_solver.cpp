#include "fem/cholmod_solver.h"

#include <cholmod.h>
#include <omp.h>

#include <algorithm>
#include <cmath>
#include <vector>

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
  bool node_blocks = false;

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
  // node_blocks: supernodal, since its factor is only exported (the solves are BlockFactor's) and
  // the numeric factorization, in dense blocks through BLAS, takes a fifth of the simplicial time
  // with OpenBLAS (about half with the reference BLAS).
  if (layout == Layout::simplicial) m_impl->common.supernodal = CHOLMOD_SIMPLICIAL;
  if (layout == Layout::node_blocks) m_impl->common.supernodal = CHOLMOD_SUPERNODAL;
  m_impl->node_blocks = layout == Layout::node_blocks;
}

namespace {

// A fill-reducing ordering of a's node graph (AMD on the pattern of its 3x3 blocks), expanded to
// each node's three rows in order; empty if a is not 3n x 3n or AMD fails.
std::vector<std::int32_t> node_ordering(const CsrMatrix& a, cholmod_common& common) {
  if (a.rows % 3 != 0) return {};
  const std::int32_t n = a.rows / 3;
  // The upper triangle of the node pattern, by columns: column J's rows are the nodes I <= J
  // coupled to it, read off row 3J of a (symmetric: a row is a column).
  std::vector<std::int32_t> p(static_cast<std::size_t>(n) + 1, 0), i;
  for (std::int32_t j = 0; j < n; ++j) {
    const auto r = static_cast<std::size_t>(3 * j);
    const auto begin = static_cast<std::size_t>(a.row_start[r]);
    for (std::size_t e = begin; e < begin + static_cast<std::size_t>(a.row_nz[r]); ++e) {
      const std::int32_t node = a.col[e] / 3;
      if (node <= j && (i.size() == static_cast<std::size_t>(p[static_cast<std::size_t>(j)]) ||
                        i.back() != node))
        i.push_back(node);
    }
    p[static_cast<std::size_t>(j) + 1] = static_cast<std::int32_t>(i.size());
  }
  cholmod_sparse g{};
  g.nrow = g.ncol = static_cast<std::size_t>(n);
  g.nzmax = std::max<std::size_t>(i.size(), 1);
  g.p = p.data();
  g.i = i.data();
  g.stype = 1;
  g.itype = CHOLMOD_INT;
  g.xtype = CHOLMOD_PATTERN;
  g.dtype = CHOLMOD_DOUBLE;
  g.sorted = 1;
  g.packed = 1;
  std::vector<std::int32_t> order(static_cast<std::size_t>(n));
  if (n > 0 && cholmod_amd(&g, nullptr, 0, order.data(), &common) == 0) return {};
  std::vector<std::int32_t> perm(static_cast<std::size_t>(a.rows));
  for (std::size_t k = 0; k < order.size(); ++k)
    for (std::int32_t c = 0; c < 3; ++c)
      perm[3 * k + static_cast<std::size_t>(c)] = 3 * order[k] + c;
  return perm;
}

}  // namespace
CholmodSolver::~CholmodSolver() = default;

bool CholmodSolver::analyze(const CsrMatrix& a) {
  Impl& m = *m_impl;
  m.free_all();
  m.rows = a.rows;
  cholmod_sparse s = Impl::view(a);
  if (m.node_blocks) {
    std::vector<std::int32_t> perm = node_ordering(a, m.common);
    if (perm.empty()) return false;
    // The given ordering as it is: no method search, no postordering (which could interleave
    // the nodes' rows).
    m.common.nmethods = 1;
    m.common.method[0].ordering = CHOLMOD_GIVEN;
    m.common.postorder = 0;
    m.factor = cholmod_analyze_p(&s, perm.data(), nullptr, 0, &m.common);
  } else {
    m.factor = cholmod_analyze(&s, &m.common);
  }
  if (m.factor == nullptr) return false;
  m.b = cholmod_zeros(static_cast<std::size_t>(a.rows), 1, CHOLMOD_REAL, &m.common);
  return m.b != nullptr;
}

bool CholmodSolver::copy_analysis(const CholmodSolver& from) {
  Impl& m = *m_impl;
  const Impl& f = *from.m_impl;
  m.free_all();
  if (f.factor == nullptr) return false;
  m.rows = f.rows;
  m.factor = cholmod_copy_factor(f.factor, &m.common);
  if (m.factor == nullptr) return false;
  m.b = cholmod_zeros(static_cast<std::size_t>(m.rows), 1, CHOLMOD_REAL, &m.common);
  return m.b != nullptr;
}

namespace {

// CHOLMOD's supernodal factorization opens OpenMP regions of a compiled-in four threads
// (CHOLMOD_OMP_NUM_THREADS), whatever the calling thread asked for. On a thread that runs alone
// (omp_get_max_threads() == 1: the lagged factor's background refresh, a one-thread FEM stage)
// they are made inactive for the call: on two cores the four threads took a refresh of the default
// scene's size (bench/fem/bench_factor.cpp, box k = 6) from 16 to 78 ms of wall time, in 245,000
// context switches over the benchmark against 3,152, and would take the solver thread's core. The
// ICV is the calling thread's own; the regions only copy and scatter, so the factor's bits do not
// depend on it.
class InactiveRegionsWhenAlone {
 public:
  InactiveRegionsWhenAlone() : m_levels(omp_get_max_active_levels()) {
    if (omp_get_max_threads() == 1) omp_set_max_active_levels(0);
  }
  ~InactiveRegionsWhenAlone() { omp_set_max_active_levels(m_levels); }
  InactiveRegionsWhenAlone(const InactiveRegionsWhenAlone&) = delete;
  InactiveRegionsWhenAlone& operator=(const InactiveRegionsWhenAlone&) = delete;

 private:
  int m_levels;
};

}  // namespace

bool CholmodSolver::factorize(const CsrMatrix& a) {
  Impl& m = *m_impl;
  m.ok_factor = false;
  if (m.factor == nullptr || a.rows != m.rows) return false;
  cholmod_sparse s = Impl::view(a);
  const InactiveRegionsWhenAlone alone;
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

namespace {

// Column j of a simplicial LDL^T factor: its diagonal entry (D_j) first, then the rows below it.
void export_simplicial(const cholmod_factor& f, LdlFactor& out) {
  const auto* lp = static_cast<const std::int32_t*>(f.p);
  const auto* li = static_cast<const std::int32_t*>(f.i);
  const auto* lnz = static_cast<const std::int32_t*>(f.nz);
  const auto* lx = static_cast<const double*>(f.x);
  for (std::size_t j = 0; j < f.n; ++j) {
    const auto begin = static_cast<std::size_t>(lp[j]);
    for (std::size_t e = begin; e < begin + static_cast<std::size_t>(lnz[j]); ++e) {
      if (static_cast<std::size_t>(li[e]) == j) {
        out.d[j] = lx[e];
      } else {
        out.row.push_back(li[e]);
        out.val.push_back(lx[e]);
      }
    }
    out.col_start[j + 1] = static_cast<std::int32_t>(out.row.size());
  }
}

// A supernodal L L^T as LDL^T: D_j = L_jj^2, L'_ij = L_ij / L_jj. Supernode s holds columns
// super[s] .. super[s+1]-1 as a dense column-major block of nsrow rows (its first nscol rows are
// the diagonal block, whose upper part is not L's). Entries that are exactly zero (the padding of
// relaxed supernodes) are left out, so the blocks are those of the simplicial factor.
void export_supernodal(const cholmod_factor& f, LdlFactor& out) {
  const auto* super = static_cast<const std::int32_t*>(f.super);
  const auto* pi = static_cast<const std::int32_t*>(f.pi);
  const auto* px = static_cast<const std::int32_t*>(f.px);
  const auto* ls = static_cast<const std::int32_t*>(f.s);
  const auto* lx = static_cast<const double*>(f.x);
  for (std::size_t sn = 0; sn < f.nsuper; ++sn) {
    const auto k1 = static_cast<std::size_t>(super[sn]);
    const auto nscol = static_cast<std::size_t>(super[sn + 1]) - k1;
    const auto nsrow = static_cast<std::size_t>(pi[sn + 1] - pi[sn]);
    const std::int32_t* rows = ls + pi[sn];
    for (std::size_t c = 0; c < nscol; ++c) {
      const double* col = lx + static_cast<std::size_t>(px[sn]) + c * nsrow;
      const double ljj = col[c];
      out.d[k1 + c] = ljj * ljj;
      for (std::size_t r = c + 1; r < nsrow; ++r) {
        if (col[r] == 0.0) continue;
        out.row.push_back(rows[r]);
        out.val.push_back(col[r] / ljj);
      }
      out.col_start[k1 + c + 1] = static_cast<std::int32_t>(out.row.size());
    }
  }
}

}  // namespace

bool CholmodSolver::export_ldl(LdlFactor& out) const {
  const Impl& m = *m_impl;
  const cholmod_factor* f = m.factor;
  if (!m.ok_factor || f == nullptr || f->itype != CHOLMOD_INT || f->xtype != CHOLMOD_REAL)
    return false;
  // Simplicial factors are LDL^T (CHOLMOD's default), supernodal ones L L^T.
  if (f->is_super == 0 && f->is_ll != 0) return false;
  const auto n = static_cast<std::size_t>(f->n);
  const auto* perm = static_cast<const std::int32_t*>(f->Perm);
  out.perm.assign(perm, perm + n);
  out.col_start.assign(n + 1, 0);
  out.row.clear();
  out.val.clear();
  out.d.assign(n, 0.0);
  if (f->is_super != 0)
    export_supernodal(*f, out);
  else
    export_simplicial(*f, out);
  return true;
}

bool CholmodSolver::analyzed() const { return m_impl->factor != nullptr; }
bool CholmodSolver::factorized() const { return m_impl->ok_factor; }

}  // namespace serosa::fem
