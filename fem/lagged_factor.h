// LaggedFactor: the preconditioner of the pcg_lagged solver, a CHOLMOD factor of the system matrix
// A = M + dt C + dt^2 K_R of an earlier step, refreshed when CG starts to need more iterations.
//
// Why: the corotated matrix changes only through the element rotations, so a factor of a recent
// step's A is nearly exact for this one: CG converges in one to a few iterations (one triangular
// solve pair each), while a numeric factorization costs many steps' worth of time. Refreshing it
// in a background thread keeps the factorization off the solver's critical path.
//
// Determinism: a refresh asked for at step k is installed at the start of step k + lag, exactly,
// waiting for the background thread if it has not finished. Which factor preconditions which step
// therefore depends only on the step count and the (deterministic) iteration counts, never on
// thread timing: a replay, or a run with background = false, gives the same bits.
//
// Warping: between refreshes the tissue turns, and A turns with it (K_R = R K R^T per element). The
// factor keeps the nodes' rotations of its step (R0_i, from the elements around node i), and is
// applied turned by W_i = R_i R0_i^T: P^{-1} = W F^{-1} W^T. A region that moved rigidly since the
// refresh is then preconditioned as if the factor were fresh, so the factor can lag further.
//
// After a cut (a new matrix structure) the integrator factors the new matrix at once
// (factor_now): an older factor no longer fits the slivers a cut leaves near the blade. Rows beyond
// the installed factor, if any, are preconditioned by Jacobi.
#pragma once

#include <cstdint>
#include <memory>
#include <span>
#include <thread>
#include <vector>

#include "engine/math.h"
#include "engine/state_codec.h"
#include "fem/cholmod_solver.h"
#include "fem/csr_matrix.h"

namespace serosa::fem {

class LaggedFactor {
 public:
  LaggedFactor() = default;
  ~LaggedFactor();
  LaggedFactor(const LaggedFactor&) = delete;
  LaggedFactor& operator=(const LaggedFactor&) = delete;

  /// Start of step `step` (the integrator's step count): installs the refresh due at this step,
  /// waiting for its thread if need be.
  void begin_step(std::uint64_t step);
  /// Factors `a` now and installs it (the first step, or after a full rebuild). `structure`
  /// identifies a's sparsity pattern (the integrator's structure counter). False if a is not SPD.
  /// node_rot: (n) the nodes' rotations at a's step (warping, above).
  bool factor_now(const CsrMatrix& a, std::uint64_t structure, std::span<const Quat> node_rot);
  /// Asks for the factor of `a` (copied), to be installed at the start of step `ready_step`.
  /// background: factor in a thread (true) or now (false; the install step is the same).
  void request(const CsrMatrix& a, std::uint64_t structure, std::uint64_t ready_step,
               bool background, std::span<const Quat> node_rot);
  /// Drops every factor and waits for any running job (the mesh was rebuilt from scratch).
  void clear();

  /// The turn of each node since the installed factor's step: warp[i] = R_i R0_i^T for the
  /// factor's nodes, the identity beyond. node_rot: (n) the nodes' rotations now; warp: (n) out.
  void warp(std::span<const Quat> node_rot, std::span<Mat3> warp) const;
  /// z = P^{-1} r = W F^{-1} W^T r on the factor's rows, inv_diag .* r beyond; rows of
  /// constrained nodes (free[i] = 0; their rows of A are diagonal) get inv_diag .* r too and are
  /// kept out of the factor's solve, so a node held or fixed since the refresh costs CG a few
  /// iterations, not hundreds. r, z, inv_diag: (3n), 3n >= rows(); free, warp: (n).
  void apply(std::span<const double> r, std::span<double> z, std::span<const double> inv_diag,
             std::span<const std::uint8_t> free, std::span<const Mat3> warp);

  /// Its part of the whole state: the matrices of the installed factor and of the pending
  /// refresh with their rotations, structures and install step (the factors themselves are
  /// recomputed from them on restore: CHOLMOD gives the same bits for the same matrix).
  void save(StateWriter& out) const;
  /// Reads what save() wrote; the pending refresh is factored in the background or now
  /// (`background`), to be installed at its step as before.
  void restore(StateReader& in, bool background);

  [[nodiscard]] bool ready() const { return m_installed != nullptr; }
  [[nodiscard]] bool pending() const { return m_job != nullptr; }
  /// Rows of the installed factor (0 when none).
  [[nodiscard]] std::int32_t rows() const { return ready() ? m_installed_rows : 0; }
  /// Structure the installed factor was computed for.
  [[nodiscard]] std::uint64_t structure() const { return m_installed_structure; }
  /// Refreshes installed so far (factor_now included).
  [[nodiscard]] std::uint64_t refreshes() const { return m_refreshes; }

 private:
  struct Job {
    CsrMatrix a;
    std::uint64_t structure = 0;
    std::uint64_t ready_step = 0;
    std::vector<Quat> node_rot;  // (n) the nodes' rotations at a's step
    std::unique_ptr<CholmodSolver> solver;
    bool analyzed = false;  // solver already holds the analysis of a's pattern
    bool ok = false;
    std::thread thread;
  };
  static void run(Job& job);
  void install();  // joins the job and installs its factor if it succeeded
  std::unique_ptr<CholmodSolver> take_spare(std::uint64_t structure, bool& analyzed);

  std::unique_ptr<Job> m_job;
  std::unique_ptr<CholmodSolver> m_installed;
  CsrMatrix m_installed_a;  // the matrix the installed factor was computed from (snapshots)
  std::int32_t m_installed_rows = 0;
  std::vector<Quat> m_installed_rot;  // (rows / 3) R0 of the installed factor
  std::uint64_t m_installed_structure = 0;
  // The factor replaced at the last install, kept with its analysis for the next refresh of the
  // same pattern (a numeric refactorization skips the symbolic analysis).
  std::unique_ptr<CholmodSolver> m_spare;
  std::uint64_t m_spare_structure = 0;
  std::uint64_t m_refreshes = 0;
  std::vector<double> m_r, m_z;  // (rows()) the turned, filtered residual and its solve
};

}  // namespace serosa::fem
