#include "fem/background_factor.h"

#include <omp.h>

#include <chrono>
#include <utility>

namespace serosa::fem {

BackgroundFactor::~BackgroundFactor() {
  m_queued.reset();
  if (m_running && m_running->thread.joinable()) m_running->thread.join();
}

void BackgroundFactor::request(CsrMatrix a, std::uint64_t version, double dt_s, int delay_ms) {
  m_any_request = true;
  m_last_version = version;
  m_last_dt = dt_s;
  Request req{std::move(a), version, dt_s, delay_ms};
  poll();
  if (m_running)
    m_queued = std::move(req);
  else
    start(std::move(req));
}

void BackgroundFactor::start(Request req) {
  auto job = std::make_unique<Job>();
  job->req = std::move(req);
  job->solver = std::make_unique<CholmodSolver>();
  Job* j = job.get();
  j->thread = std::thread([j] {
    omp_set_num_threads(1);  // the solver's thread has the other core (fem/cholmod_solver.cpp)
    if (j->req.delay_ms > 0)
      std::this_thread::sleep_for(std::chrono::milliseconds(j->req.delay_ms));
    j->ok = j->solver->analyze(j->req.a) && j->solver->factorize(j->req.a);
    j->done.store(true, std::memory_order_release);
  });
  m_running = std::move(job);
}

void BackgroundFactor::finish() {
  m_running->thread.join();
  // Install unless a newer request superseded it (then the queued job replaces it soon).
  const bool superseded = m_queued.has_value() && m_queued->version != m_running->req.version;
  if (m_running->ok && !superseded) {
    m_current = std::move(m_running->solver);
    m_current_version = m_running->req.version;
    m_current_dt = m_running->req.dt_s;
  }
  m_running.reset();
}

void BackgroundFactor::poll() {
  if (m_running && m_running->done.load(std::memory_order_acquire)) finish();
  if (!m_running && m_queued) {
    Request next = std::move(*m_queued);
    m_queued.reset();
    start(std::move(next));
  }
}

void BackgroundFactor::wait() {
  while (m_running) {
    finish();
    if (m_queued) {
      Request next = std::move(*m_queued);
      m_queued.reset();
      start(std::move(next));
    }
  }
}

CholmodSolver* BackgroundFactor::factor_for(std::uint64_t version) {
  return m_current && m_current_version == version && m_current->factorized() ? m_current.get()
                                                                              : nullptr;
}

bool BackgroundFactor::requested(std::uint64_t version, double dt_s) const {
  return m_any_request && m_last_version == version && m_last_dt == dt_s;
}

}  // namespace serosa::fem
