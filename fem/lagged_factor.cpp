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
  m_spare.reset();
  m_installed_rows = 0;
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
