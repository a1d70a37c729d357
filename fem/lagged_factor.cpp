#include "fem/lagged_factor.h"

#include <omp.h>

#include <algorithm>
#include <chrono>
#include <utility>

namespace serosa::fem {
namespace {

// A record no longer in use: emptied (its buffers kept for the next), so that the state holds
// nothing of it.
void empty(CsrMatrix& a) {
  a.rows = 0;
  a.row_start.clear();
  a.row_nz.clear();
  a.col.clear();
  a.val.clear();
}
void empty(FactoredMatrix& f) {
  f.on = false;
  empty(f.a);
  f.node_rot.clear();
  f.tet_rot.clear();
  f.free.clear();
  f.structure = 0;
  f.ready_step = 0;
}
void empty(FactorPatch& p) {
  p.on = false;
  empty(p.a);
  empty(p.tu);
  p.nodes.clear();
  p.free.clear();
  p.tet_rot.clear();
  p.structure = 0;
}

}  // namespace

LaggedFactor::~LaggedFactor() {
  if (m_job && m_job->thread.joinable()) m_job->thread.join();
}

void LaggedFactor::run(Job& job) {
  if (!job.analyzed)
    job.analyzed = job.analysis_of != nullptr ? job.solver->copy_analysis(*job.analysis_of)
                                              : job.solver->analyze(job.a);
  job.ok = job.analyzed && job.solver->factorize(job.a);
  // The block copy the solves use (CHOLMOD's own solve stands in when it cannot be made).
  if (!job.ok || !job.solver->export_ldl(job.ldl) || !job.blocks.build(job.ldl)) job.blocks.clear();
}

std::unique_ptr<CholmodSolver> LaggedFactor::take_spare(std::uint64_t structure, bool& analyzed) {
  analyzed = m_spare != nullptr && m_spare_structure == structure && m_spare->analyzed();
  if (m_spare) return std::move(m_spare);
  return std::make_unique<CholmodSolver>(CholmodSolver::Layout::node_blocks);
}

void LaggedFactor::install() {
  if (m_job->thread.joinable()) {
    const auto start = std::chrono::steady_clock::now();
    m_job->thread.join();
    m_last_wait_ms +=
        std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
  }
  if (m_job->ok) {
    m_spare = std::move(m_installed);
    m_spare_structure = m_b->installed.structure;
    m_installed = std::move(m_job->solver);
    m_installed_rows = m_job->a.rows;
    std::swap(m_installed_blocks, m_job->blocks);
    // Swapped, not moved: the record keeps the replaced buffers for the next request to copy into.
    std::swap(m_b->installed, m_b->pending);
    m_b->installed.structure = m_job->structure;
    m_b->installed.ready_step = 0;  // (a pending refresh's)
    ++m_b->refreshes;
    // The patch stays until the integrator finds the installed factor fits (patch_fits).
  }
  empty(m_b->pending);
  m_job->solver.reset();
  m_recycled = std::move(m_job);
}

// A job for `a`, in the buffers of the last one when there is one: the copy of a into them
// touches no new pages (a fresh 2 MB copy cost the step after a cut about half a millisecond).
std::unique_ptr<LaggedFactor::Job> LaggedFactor::new_job(const CsrMatrix& a,
                                                         std::uint64_t structure) {
  std::unique_ptr<Job> job = m_recycled ? std::move(m_recycled) : std::make_unique<Job>();
  job->ok = false;
  job->analyzed = false;
  job->analysis_of = nullptr;
  copy_packed(a, job->a);
  job->structure = structure;
  return job;
}

// The thread factors its own copy of the matrix (the state may be replaced meanwhile); the
// state's record of it is what a snapshot keeps.
void LaggedFactor::record_pending(const CsrMatrix& a, std::uint64_t structure,
                                  std::uint64_t ready_step, std::span<const Quat> node_rot,
                                  std::span<const Quat> tet_rot,
                                  std::span<const std::uint8_t> free) {
  FactoredMatrix& p = m_b->pending;
  p.on = true;
  copy_packed(a, p.a);
  p.node_rot.assign(node_rot.begin(), node_rot.end());
  p.tet_rot.assign(tet_rot.begin(), tet_rot.end());
  p.free.assign(free.begin(), free.end());
  p.structure = structure;
  p.ready_step = ready_step;
}

std::int64_t LaggedFactor::rows_needed() const {
  std::int64_t rows = ready() ? m_installed_rows : 0;
  if (m_job) rows = std::max<std::int64_t>(rows, m_job->a.rows);
  if (m_patch && !m_b->patch.nodes.empty())
    rows =
        std::max<std::int64_t>(rows, 3 * (static_cast<std::int64_t>(m_b->patch.nodes.back()) + 1));
  if (m_patch) {
    for (const std::int32_t c : m_b->patch.tu.col) rows = std::max<std::int64_t>(rows, c + 1);
    rows = std::max<std::int64_t>(rows, 3 * static_cast<std::int64_t>(m_b->patch.free.size()));
  }
  return rows;
}

bool LaggedFactor::patch(const CsrMatrix& a, std::uint64_t structure,
                         std::span<const std::uint8_t> in_patch, std::span<const std::uint8_t> free,
                         std::span<const Quat> tet_rot) {
  std::vector<std::int32_t> nodes;
  for (std::size_t i = 0; i < in_patch.size() && 3 * i < static_cast<std::size_t>(a.rows); ++i)
    if (in_patch[i] != 0 && i < free.size() && free[i] != 0)
      nodes.push_back(static_cast<std::int32_t>(i));
  std::vector<std::int32_t> index(in_patch.size(), -1);
  for (std::size_t k = 0; k < nodes.size(); ++k)
    index[static_cast<std::size_t>(nodes[k])] = static_cast<std::int32_t>(k);
  // The patch's rows of A, packed, split by column: A_TT (patch-local columns, still ascending:
  // ids ascend) and A_TU (global columns of the other nodes).
  CsrMatrix tt, tu;
  tt.rows = tu.rows = static_cast<std::int32_t>(3 * nodes.size());
  tt.row_start.push_back(0);
  tu.row_start.push_back(0);
  for (const std::int32_t i : nodes)
    for (std::int32_t c = 0; c < 3; ++c) {
      const auto r = static_cast<std::size_t>(3 * i + c);
      const auto begin = static_cast<std::size_t>(a.row_start[r]);
      const auto end = begin + static_cast<std::size_t>(a.row_nz[r]);
      for (std::size_t e = begin; e < end; ++e) {
        const auto j = static_cast<std::size_t>(a.col[e]);
        const std::int32_t local = j / 3 < index.size() ? index[j / 3] : -1;
        CsrMatrix& to = local >= 0 ? tt : tu;
        to.col.push_back(local >= 0 ? 3 * local + static_cast<std::int32_t>(j % 3)
                                    : static_cast<std::int32_t>(j));
        to.val.push_back(a.val[e]);
      }
      for (CsrMatrix* m : {&tt, &tu}) {
        m->row_nz.push_back(static_cast<std::int32_t>(m->col.size()) - m->row_start.back());
        m->row_start.push_back(static_cast<std::int32_t>(m->col.size()));
      }
    }
  return install_patch(std::move(tt), std::move(tu), std::move(nodes), structure,
                       std::vector<std::uint8_t>(free.begin(), free.end()),
                       std::vector<Quat>(tet_rot.begin(), tet_rot.end()));
}

bool LaggedFactor::patch_fits(std::uint64_t structure, std::span<const std::uint8_t> free) const {
  return m_patch && m_b->patch.structure == structure &&
         std::equal(free.begin(), free.end(), m_b->patch.free.begin(), m_b->patch.free.end());
}

bool LaggedFactor::kinds_changed(std::span<const std::uint8_t> free,
                                 std::span<std::uint8_t> changed) const {
  bool any = false;
  for (std::size_t i = 0; i < changed.size(); ++i) {
    changed[i] =
        i < m_b->installed.free.size() && i < free.size() && free[i] != m_b->installed.free[i];
    any = any || changed[i] != 0;
  }
  return any;
}

bool LaggedFactor::install_patch(CsrMatrix tt, CsrMatrix tu, std::vector<std::int32_t> nodes,
                                 std::uint64_t structure, std::vector<std::uint8_t> free,
                                 std::vector<Quat> tet_rot) {
  // The same rows as the patch in use (a misfit's patch, made anew each step while tets turn):
  // the same pattern, whose analysis is kept (CHOLMOD orders by pattern alone, so the bits are
  // those of a fresh analysis).
  const bool same = m_patch != nullptr && m_b->patch.structure == structure &&
                    nodes == m_b->patch.nodes && tt.row_nz == m_b->patch.a.row_nz &&
                    tt.col == m_b->patch.a.col;
  std::unique_ptr<CholmodSolver> solver =
      same ? std::move(m_patch)
           : std::make_unique<CholmodSolver>(CholmodSolver::Layout::simplicial);
  m_patch.reset();
  empty(m_b->patch);
  if (nodes.empty()) return false;
  if ((!same && !solver->analyze(tt)) || !solver->factorize(tt)) return false;
  m_patch = std::move(solver);
  m_b->patch.on = true;
  m_b->patch.a = std::move(tt);
  m_b->patch.tu = std::move(tu);
  m_b->patch.nodes = std::move(nodes);
  m_b->patch.structure = structure;
  m_b->patch.free = std::move(free);
  m_b->patch.tet_rot = std::move(tet_rot);
  m_patch_index.assign(static_cast<std::size_t>(m_b->patch.nodes.back()) + 1, -1);
  for (std::size_t k = 0; k < m_b->patch.nodes.size(); ++k)
    m_patch_index[static_cast<std::size_t>(m_b->patch.nodes[k])] = static_cast<std::int32_t>(k);
  return true;
}

void LaggedFactor::begin_step(std::uint64_t step) {
  m_last_wait_ms = 0.0;
  if (m_job && step >= m_job->ready_step) install();
}

bool LaggedFactor::factor_now(const CsrMatrix& a, std::uint64_t structure,
                              std::span<const Quat> node_rot, std::span<const Quat> tet_rot,
                              std::span<const std::uint8_t> free) {
  clear();
  std::unique_ptr<Job> job = new_job(a, structure);
  record_pending(a, structure, 0, node_rot, tet_rot, free);
  job->solver = std::make_unique<CholmodSolver>(CholmodSolver::Layout::node_blocks);
  run(*job);
  m_job = std::move(job);
  const bool ok = m_job->ok;
  install();
  return ok;
}

void LaggedFactor::warm_up() {
  if (!ready() || m_job || m_spare) return;
  std::unique_ptr<Job> job = new_job(m_b->installed.a, m_b->installed.structure);
  job->solver = std::make_unique<CholmodSolver>(CholmodSolver::Layout::node_blocks);
  job->analysis_of = m_installed.get();
  run(*job);
  if (job->ok) {
    m_spare = std::move(job->solver);
    m_spare_structure = m_b->installed.structure;
  }
  job->solver.reset();
  m_recycled = std::move(job);
}

void LaggedFactor::request(const CsrMatrix& a, std::uint64_t structure, std::uint64_t ready_step,
                           bool background, std::span<const Quat> node_rot,
                           std::span<const Quat> tet_rot, std::span<const std::uint8_t> free) {
  if (m_job) install();  // one job at a time; callers ask only when none is pending
  std::unique_ptr<Job> job = new_job(a, structure);
  record_pending(a, structure, ready_step, node_rot, tet_rot, free);
  job->ready_step = ready_step;
  job->solver = take_spare(structure, job->analyzed);
  job->analysis_of = !job->analyzed && m_installed != nullptr &&
                             m_b->installed.structure == structure && m_installed->analyzed()
                         ? m_installed.get()
                         : nullptr;
  Job* j = job.get();
  if (background)
    j->thread = std::thread([j] {
      // One thread: the solver's thread has the other core (fem/cholmod_solver.cpp).
      omp_set_num_threads(1);
      run(*j);
    });
  else
    run(*j);
  m_job = std::move(job);
}

void LaggedFactor::clear() {
  if (m_job && m_job->thread.joinable()) m_job->thread.join();
  m_job.reset();
  m_installed.reset();
  m_installed_blocks.clear();
  empty(m_b->installed);
  empty(m_b->pending);
  m_spare.reset();
  m_installed_rows = 0;
  m_patch.reset();
  empty(m_b->patch);
}

void LaggedFactor::drop_patch() {
  m_patch.reset();
  empty(m_b->patch);
}

bool LaggedFactor::adopt(bool background) {
  const LaggedBlock saved = *m_b;  // clear() and the factoring below rewrite the record
  clear();
  bool ok = true;
  if (saved.installed.on)
    ok = factor_now(saved.installed.a, saved.installed.structure, saved.installed.node_rot,
                    saved.installed.tet_rot, saved.installed.free);
  const FactoredMatrix& p = saved.pending;
  if (ok && p.on)
    request(p.a, p.structure, p.ready_step, background, p.node_rot, p.tet_rot, p.free);
  const FactorPatch& t = saved.patch;
  if (ok && t.on) ok = install_patch(t.a, t.tu, t.nodes, t.structure, t.free, t.tet_rot);
  m_b->refreshes = saved.refreshes;
  return ok;
}

void LaggedFactor::relabel_tets(const TopologyDelta& delta, std::size_t tets) {
  const Quat none(0.0, 0.0, 0.0, 0.0);
  const auto relabel = [&](std::vector<Quat>& q) {
    if (q.empty()) return;
    for (const std::int32_t slot : delta.slot_of_added) {
      const auto u = static_cast<std::size_t>(slot);
      if (u >= q.size()) q.resize(u + 1, none);
      q[u] = none;
    }
    for (const auto& [from, to] : delta.moved_tets)
      q[static_cast<std::size_t>(to)] = q[static_cast<std::size_t>(from)];
    q.resize(tets, none);
  };
  relabel(m_b->installed.tet_rot);
  if (m_b->pending.on) relabel(m_b->pending.tet_rot);  // the thread reads only the job's matrix
}

void LaggedFactor::warp(std::span<const Quat> node_rot, std::span<Mat3> warp) const {
  const std::size_t nf = m_b->installed.node_rot.size();
  for (std::size_t i = 0; i < warp.size(); ++i)
    warp[i] = i < nf
                  ? Mat3((node_rot[i] * m_b->installed.node_rot[i].conjugate()).toRotationMatrix())
                  : Mat3::Identity();
}

// Without a patch: z = W F^{-1} W^T r on the factor's free rows, Jacobi on the others. With one,
// the block LU of A split into the patch's rows T and the others U, with the patch's factor for
// A_TT and the installed factor (T rows masked out) standing in for the inverse of U's Schur
// complement:
//   w = A_TT^{-1} r_T;  y_U = S^{-1} (r_U - A_UT w);  z_T = w - A_TT^{-1} A_TU y_U;  z_U = y_U.
// That is L^{-T} D^{-1} L^{-1} with SPD D: symmetric positive definite, as CG needs. Block Jacobi
// (w and y alone) ignores A_UT, which across a cut's touched rows is as stiff as the tissue:
// CG took 68 iterations with it against a handful with the coupling.
void LaggedFactor::apply(std::span<const double> r, std::span<double> z,
                         std::span<const double> inv_diag, std::span<const std::uint8_t> free,
                         std::span<const Mat3> warp) {
  std::span<const double> rhs = r;
  if (m_patch) {
    patch_solve(r, free, m_w);  // w = A_TT^{-1} r_T
    m_ru.assign(r.begin(), r.end());
    multiply_ut(m_w, -1.0, m_ru);  // r_U - A_UT w
    rhs = m_ru;
  }
  factor_solve(rhs, z, inv_diag, free, warp);
  if (!m_patch) return;
  // z_T = w - A_TT^{-1} (A_TU y_U)
  m_ty.assign(3 * m_b->patch.nodes.size(), 0.0);
  for (std::size_t k = 0; k < m_ty.size(); ++k) {
    double sum = 0.0;
    const auto begin = static_cast<std::size_t>(m_b->patch.tu.row_start[k]);
    const auto end = begin + static_cast<std::size_t>(m_b->patch.tu.row_nz[k]);
    for (std::size_t e = begin; e < end; ++e) {
      const auto j = static_cast<std::size_t>(m_b->patch.tu.col[e]);
      if (j < z.size() && !in_patch(j / 3)) sum += m_b->patch.tu.val[e] * z[j];
    }
    m_ty[k] = sum;
  }
  m_pz.resize(m_ty.size());
  m_patch->solve(m_ty, m_pz);
  for (std::size_t k = 0; k < m_b->patch.nodes.size(); ++k) {
    const auto i = static_cast<std::size_t>(m_b->patch.nodes[k]);
    if (i >= free.size() || free[i] == 0) continue;
    for (std::size_t c = 0; c < 3; ++c) z[3 * i + c] = m_w[3 * k + c] - m_pz[3 * k + c];
  }
}

// w = A_TT^{-1} r_T on the patch's nodes still free (0 for the others).
void LaggedFactor::patch_solve(std::span<const double> r, std::span<const std::uint8_t> free,
                               std::vector<double>& w) {
  m_pr.resize(3 * m_b->patch.nodes.size());
  for (std::size_t k = 0; k < m_b->patch.nodes.size(); ++k) {
    const auto i = static_cast<std::size_t>(m_b->patch.nodes[k]);
    for (std::size_t c = 0; c < 3; ++c)
      m_pr[3 * k + c] = i < free.size() && free[i] != 0 ? r[3 * i + c] : 0.0;
  }
  w.resize(m_pr.size());
  m_patch->solve(m_pr, w);
}

// out_U += s A_UT w (A_UT = A_TU^T: the patch's rows give its columns).
void LaggedFactor::multiply_ut(std::span<const double> w, double s, std::span<double> out) const {
  for (std::size_t k = 0; k < w.size(); ++k) {
    const auto begin = static_cast<std::size_t>(m_b->patch.tu.row_start[k]);
    const auto end = begin + static_cast<std::size_t>(m_b->patch.tu.row_nz[k]);
    for (std::size_t e = begin; e < end; ++e) {
      const auto j = static_cast<std::size_t>(m_b->patch.tu.col[e]);
      if (j < out.size()) out[j] += s * m_b->patch.tu.val[e] * w[k];
    }
  }
}

// z = W F^{-1} W^T r on the factor's free rows outside the patch, inv_diag .* r on the others
// (the patch's rows are overwritten by apply()).
void LaggedFactor::factor_solve(std::span<const double> r, std::span<double> z,
                                std::span<const double> inv_diag,
                                std::span<const std::uint8_t> free, std::span<const Mat3> warp) {
  const auto nf = static_cast<std::size_t>(m_installed_rows);
  const auto by_factor = [&](std::size_t i) { return free[i] != 0 && !in_patch(i); };
  m_r.resize(nf);
  m_z.resize(nf);
  for (std::size_t i = 0; 3 * i < nf; ++i) {
    const Vec3 ri = by_factor(i)
                        ? Vec3(warp[i].transpose() * Vec3(r[3 * i], r[3 * i + 1], r[3 * i + 2]))
                        : Vec3::Zero();
    for (std::size_t c = 0; c < 3; ++c) m_r[3 * i + c] = ri[static_cast<Eigen::Index>(c)];
  }
  if (m_installed_blocks.rows() == m_installed_rows)
    m_installed_blocks.solve(m_r, m_z);
  else
    m_installed->solve(m_r, m_z);
  for (std::size_t i = 0; 3 * i < nf; ++i) {
    const Vec3 zi = warp[i] * Vec3(m_z[3 * i], m_z[3 * i + 1], m_z[3 * i + 2]);
    for (std::size_t c = 0; c < 3; ++c)
      z[3 * i + c] =
          by_factor(i) ? zi[static_cast<Eigen::Index>(c)] : inv_diag[3 * i + c] * r[3 * i + c];
  }
  for (std::size_t i = nf; i < r.size(); ++i) z[i] = inv_diag[i] * r[i];
}

}  // namespace serosa::fem
