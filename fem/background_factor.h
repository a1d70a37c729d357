// BackgroundFactor: the CHOLMOD factor that preconditions CG in the pcg_cholmod solver, computed in
// a background std::thread so that no solver step ever waits for a factorization. After a topology
// change the integrator requests the factor of the new rest-state matrix and keeps stepping with
// Jacobi (the old factor has the old size) until it is ready; after a change of dt it keeps using
// the old factor (still SPD, so still a valid preconditioner) until the new one is ready.
//
// One job runs at a time. A request made while a job runs is queued (replacing any earlier queued
// request) and started by the first poll() after the running job ends; a finished job whose
// version has since been superseded is dropped. poll() never blocks: it joins only threads that
// have already signalled completion.
#pragma once

#include <atomic>
#include <cstdint>
#include <memory>
#include <optional>
#include <thread>

#include "fem/cholmod_solver.h"
#include "fem/csr_matrix.h"

namespace serosa::fem {

class BackgroundFactor {
 public:
  BackgroundFactor() = default;
  ~BackgroundFactor();
  BackgroundFactor(const BackgroundFactor&) = delete;
  BackgroundFactor& operator=(const BackgroundFactor&) = delete;

  /// Asks for the factor of `a` (moved in) for topology `version` and time step dt_s. Never
  /// blocks. delay_ms: the job sleeps this long before analysing (tests use it to make "the
  /// factor is not ready yet" deterministic; 0 otherwise).
  void request(CsrMatrix a, std::uint64_t version, double dt_s, int delay_ms = 0);
  /// Installs a finished job and starts a queued one. Never blocks.
  void poll();
  /// Blocks until no job runs or waits (tests; shutdown), then installs the result.
  void wait();

  /// The installed factor if it was computed for `version` (and factored successfully).
  [[nodiscard]] CholmodSolver* factor_for(std::uint64_t version);
  /// dt the installed factor was computed for (s); negative when there is none.
  [[nodiscard]] double factor_dt() const { return m_current ? m_current_dt : -1.0; }
  /// True if the last request (running or queued) is for (version, dt_s).
  [[nodiscard]] bool requested(std::uint64_t version, double dt_s) const;
  /// True while a job runs or waits.
  [[nodiscard]] bool busy() const { return m_running != nullptr || m_queued.has_value(); }

 private:
  struct Request {
    CsrMatrix a;
    std::uint64_t version = 0;
    double dt_s = 0.0;
    int delay_ms = 0;
  };
  struct Job {
    Request req;
    std::unique_ptr<CholmodSolver> solver;
    std::atomic<bool> done{false};
    bool ok = false;
    std::thread thread;
  };
  void start(Request req);
  void finish();  // joins the running job (done or not) and installs it if current

  std::unique_ptr<Job> m_running;
  std::optional<Request> m_queued;
  std::unique_ptr<CholmodSolver> m_current;
  std::uint64_t m_current_version = 0;
  double m_current_dt = -1.0;
  std::uint64_t m_last_version = 0;
  double m_last_dt = -1.0;
  bool m_any_request = false;
};

}  // namespace serosa::fem
