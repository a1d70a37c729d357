#include "fem/lagged_factor.h"

#include <utility>

namespace serosa::fem {

LaggedFactor::~LaggedFactor() {
  if (m_job && m_job->thread.joinable()) m_job->thread.join();
}

void LaggedFactor::run(Job& job) {
  if (!job.analyzed) job.analyzed = job.solver->analyze(job.a);
  job.ok = job.analyzed && job.solver->factorize(job.a);
}

std::unique_ptr<CholmodSolver> LaggedFactor::take_spare(std::uint64_t structure, bool& analyzed) {
  analyzed = m_spare != nullptr && m_spare_structure == structure && m_spare->analyzed();
  if (m_spare) return std::move(m_spare);
  return std::make_unique<CholmodSolver>(CholmodSolver::Layout::simplicial);
}

void LaggedFactor::install() {
  if (m_job->thread.joinable()) m_job->thread.join();
  if (m_job->ok) {
    m_spare = std::move(m_installed);
    m_spare_structure = m_installed_structure;
    m_installed = std::move(m_job->solver);
    m_installed_rows = m_job->a.rows;
    m_installed_a = std::move(m_job->a);
    m_installed_rot = std::move(m_job->node_rot);
    m_installed_structure = m_job->structure;
    ++m_refreshes;
  }
  m_job.reset();
}

void LaggedFactor::begin_step(std::uint64_t step) {
  if (m_job && step >= m_job->ready_step) install();
}

bool LaggedFactor::factor_now(const CsrMatrix& a, std::uint64_t structure,
                              std::span<const Quat> node_rot) {
  clear();
  auto job = std::make_unique<Job>();
  job->a = a;
  job->node_rot.assign(node_rot.begin(), node_rot.end());
  job->structure = structure;
  job->solver = std::make_unique<CholmodSolver>(CholmodSolver::Layout::simplicial);
  run(*job);
  m_job = std::move(job);
  const bool ok = m_job->ok;
  install();
  return ok;
}

void LaggedFactor::request(const CsrMatrix& a, std::uint64_t structure, std::uint64_t ready_step,
                           bool background, std::span<const Quat> node_rot) {
  if (m_job) install();  // one job at a time; callers ask only when none is pending
  auto job = std::make_unique<Job>();
  job->a = a;
  job->node_rot.assign(node_rot.begin(), node_rot.end());
  job->structure = structure;
  job->ready_step = ready_step;
  job->solver = take_spare(structure, job->analyzed);
  Job* j = job.get();
  if (background)
    j->thread = std::thread([j] { run(*j); });
  else
    run(*j);
  m_job = std::move(job);
}

void LaggedFactor::clear() {
  if (m_job && m_job->thread.joinable()) m_job->thread.join();
  m_job.reset();
  m_installed.reset();
  m_installed_a = CsrMatrix{};
  m_spare.reset();
  m_installed_rows = 0;
}

namespace {

// Packed: each row's used entries only, so that the bytes depend on the matrix, not on the slack
// its pattern's storage happens to leave (a rebuilt pattern is compact, an updated one is not).
void write_csr(StateWriter& out, const CsrMatrix& a) {
  out.u32(static_cast<std::uint32_t>(a.rows));
  std::vector<std::int32_t> col;
  std::vector<double> val;
  for (std::int32_t r = 0; r < a.rows; ++r) {
    const auto begin = static_cast<std::size_t>(a.row_start[static_cast<std::size_t>(r)]);
    const auto nz = static_cast<std::size_t>(a.row_nz[static_cast<std::size_t>(r)]);
    col.insert(col.end(), a.col.begin() + static_cast<std::ptrdiff_t>(begin),
               a.col.begin() + static_cast<std::ptrdiff_t>(begin + nz));
    val.insert(val.end(), a.val.begin() + static_cast<std::ptrdiff_t>(begin),
               a.val.begin() + static_cast<std::ptrdiff_t>(begin + nz));
  }
  out.array(a.row_nz);
  out.array(col);
  out.array(val);
}

CsrMatrix read_csr(StateReader& in) {
  CsrMatrix a;
  a.rows = static_cast<std::int32_t>(in.u32());
  in.array(a.row_nz);
  in.array(a.col);
  in.array(a.val);
  const auto rows = static_cast<std::size_t>(a.rows);
  if (a.rows < 0 || a.row_nz.size() != rows || a.col.size() != a.val.size())
    in.fail("a factor's matrix is inconsistent");
  a.row_start.assign(rows + 1, 0);
  std::int64_t at = 0;
  for (std::size_t r = 0; r < rows; ++r) {
    a.row_start[r] = static_cast<std::int32_t>(at);
    if (a.row_nz[r] < 0) in.fail("a factor's matrix has a row of negative length");
    at += a.row_nz[r];
    if (at > static_cast<std::int64_t>(a.col.size()))
      in.fail("a factor's matrix rows run past its entries");
  }
  a.row_start[rows] = static_cast<std::int32_t>(at);
  for (std::int32_t c : a.col)
    if (c < 0 || c >= a.rows) in.fail("a factor's matrix has a column out of range");
  return a;
}

}  // namespace

void LaggedFactor::save(StateWriter& out) const {
  out.u64(m_refreshes);
  out.u8(ready() ? 1 : 0);
  if (ready()) {
    write_csr(out, m_installed_a);
    out.array(m_installed_rot);
    out.u64(m_installed_structure);
  }
  out.u8(m_job ? 1 : 0);
  if (m_job) {
    write_csr(out, m_job->a);  // read-only in the job's thread too
    out.array(m_job->node_rot);
    out.u64(m_job->structure);
    out.u64(m_job->ready_step);
  }
}

void LaggedFactor::restore(StateReader& in, bool background) {
  clear();
  const std::uint64_t refreshes = in.u64();
  if (in.u8() != 0) {
    CsrMatrix a = read_csr(in);
    std::vector<Quat> rot;
    in.array(rot);
    const std::uint64_t structure = in.u64();
    if (!factor_now(a, structure, rot)) in.fail("the installed factor's matrix is not SPD");
  }
  if (in.u8() != 0) {
    CsrMatrix a = read_csr(in);
    std::vector<Quat> rot;
    in.array(rot);
    const std::uint64_t structure = in.u64();
    const std::uint64_t ready_step = in.u64();
    request(a, structure, ready_step, background, rot);
  }
  m_refreshes = refreshes;
}

void LaggedFactor::warp(std::span<const Quat> node_rot, std::span<Mat3> warp) const {
  const std::size_t nf = m_installed_rot.size();
  for (std::size_t i = 0; i < warp.size(); ++i)
    warp[i] = i < nf ? Mat3((node_rot[i] * m_installed_rot[i].conjugate()).toRotationMatrix())
                     : Mat3::Identity();
}

void LaggedFactor::apply(std::span<const double> r, std::span<double> z,
                         std::span<const double> inv_diag, std::span<const std::uint8_t> free,
                         std::span<const Mat3> warp) {
  const auto nf = static_cast<std::size_t>(m_installed_rows);
  m_r.resize(nf);
  m_z.resize(nf);
  // W^T r on the free nodes of the factor, 0 on constrained ones.
  for (std::size_t i = 0; 3 * i < nf; ++i) {
    const Vec3 ri = free[i] != 0
                        ? Vec3(warp[i].transpose() * Vec3(r[3 * i], r[3 * i + 1], r[3 * i + 2]))
                        : Vec3::Zero();
    for (std::size_t c = 0; c < 3; ++c) m_r[3 * i + c] = ri[static_cast<Eigen::Index>(c)];
  }
  m_installed->solve(m_r, m_z);
  for (std::size_t i = 0; 3 * i < nf; ++i) {
    const Vec3 zi = warp[i] * Vec3(m_z[3 * i], m_z[3 * i + 1], m_z[3 * i + 2]);
    for (std::size_t c = 0; c < 3; ++c)
      z[3 * i + c] =
          free[i] != 0 ? zi[static_cast<Eigen::Index>(c)] : inv_diag[3 * i + c] * r[3 * i + c];
  }
  for (std::size_t i = nf; i < r.size(); ++i) z[i] = inv_diag[i] * r[i];
}

}  // namespace serosa::fem
