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
// After a cut (a new matrix structure) the installed factor no longer fits the rows the cut changed
// (the slivers near the blade, the new nodes): Jacobi there took CG to its 200-iteration cap. The
// integrator then patches it (patch()): the rows of the nodes the cut touched, and rings of
// neighbours around them (SolverSettings::patch_rings), get a factor of their own, of the new
// matrix restricted to them (a few hundred rows, factored in well under a millisecond), and the
// installed factor, with those rows masked out of its solve, stands in for the rest: a block LU of
// the new matrix with the old factor in the Schur complement's place (LaggedFactor::apply). The
// rings keep the patch's edge, where the two meet, in rows the cut did not change, and CG needs a
// few more iterations a step than usual (the default scene's cut: 8 with two rings, against 10
// with one). A factor of the new structure is refreshed in the background meanwhile and
// installed `lag` steps later; the integrator then drops the patch. So a cut costs the step a
// local factorization and some CG iterations, not a global factorization. The first step and a
// full rebuild still factor at once (factor_now).
//
// A grasp, or letting go, changes rows too: a node held since the factor's step has a diagonal
// row now, and its free neighbours lose their coupling to it, which the factor (of the free node's
// rows) does not know; a node let go has full rows the factor took as diagonal. Masking the held
// rows alone left CG at 16-20 iterations a step on the default scene's grasp (68 on a released
// bar's) until the refresh came. So the factor keeps the free mask of its matrix, and the nodes
// whose kind changed since are patched like a cut's, with their rings (5-8 iterations on that
// grasp, 8-11 on that bar), until a refresh that knows the new mask is installed.
//
// Misfit: the warp turns node i's rows as one, which fits while the tets around the node turn with
// it, not while one inverts (the endoloop's cinch crushes about a hundred), or a cut's fresh
// pieces recoil. So the factor keeps its tets' rotations too, and a node one of whose tets turned
// otherwise than the node since the factor's step, by more than SolverSettings::misfit_rad, is
// patched on this step like a cut's (the patch itself, not warped, is made anew once one of its
// tets turned that much since it was made, or a node the factor no longer fits lies outside it;
// a patch that still fits and holds every such node is kept). On the default procedure this took
// the steps after the transection from 110 CG iterations to under 10, and the cinch's from up to
// 100 to 3-6.
// The patch keeps its analysis while its rows stay the same (CHOLMOD orders by pattern alone),
// and a refresh of the installed factor's structure copies its analysis, leaving the background
// thread only the numeric factorization.
#pragma once

#include <cstdint>
#include <memory>
#include <span>
#include <thread>
#include <vector>

#include "engine/bound_block.h"
#include "engine/fem_block.h"
#include "engine/math.h"
#include "engine/topology_delta.h"
#include "fem/block_factor.h"
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
  /// Wall time the last begin_step() waited for the background thread to finish the refresh it
  /// installed, ms (0 when it was done in time or none was due). A measure of this run's
  /// machine, not part of the schedule: it never changes a result.
  [[nodiscard]] double last_wait_ms() const { return m_last_wait_ms; }
  /// Factors `a` now and installs it (the first step, or after a full rebuild). `structure`
  /// identifies a's sparsity pattern (the integrator's structure counter). False if a is not SPD.
  /// node_rot: (n) the nodes' rotations at a's step (warping, above); tet_rot: (m) the tets'
  /// rotations then (misfit, above); free: (n) 1 where the node took part in a's solve (a's rows
  /// of the others are diagonal).
  bool factor_now(const CsrMatrix& a, std::uint64_t structure, std::span<const Quat> node_rot,
                  std::span<const Quat> tet_rot, std::span<const std::uint8_t> free);
  /// At load time, after factor_now(): factors the installed factor's matrix once more into the
  /// spare and the job buffers the refreshes reuse, so that the first refresh, in the background
  /// while the run steps, finds its analysis done and its memory touched (it took twice as long as
  /// the later ones, and the step that installed it waited). Changes no result.
  void warm_up();
  /// Asks for the factor of `a` (copied), to be installed at the start of step `ready_step`.
  /// background: factor in a thread (true) or now (false; the install step is the same).
  void request(const CsrMatrix& a, std::uint64_t structure, std::uint64_t ready_step,
               bool background, std::span<const Quat> node_rot, std::span<const Quat> tet_rot,
               std::span<const std::uint8_t> free);
  /// The nodes held or let go since the installed factor's matrix: changed[i] = 1 where free[i]
  /// differs from the factor's mask (nodes beyond the factor: 0, a cut's delta covers them).
  /// True if there is any. free, changed: (n).
  bool kinds_changed(std::span<const std::uint8_t> free, std::span<std::uint8_t> changed) const;
  /// After a cut, a grasp or a release: factors `a` (the matrix of structure `structure`)
  /// restricted to the rows of the nodes with in_patch[i] && free[i] (the nodes the cuts since the
  /// installed factor touched, new nodes included, or held or let go since, with their rings);
  /// apply() then solves those rows with it until the integrator drops it (drop_patch) or
  /// replaces it. False if that submatrix is not SPD (no patch then).
  /// in_patch, free: (n).
  /// tet_rot: (m) the tets' rotations now (the patch's own misfit, patch_rotations()).
  bool patch(const CsrMatrix& a, std::uint64_t structure, std::span<const std::uint8_t> in_patch,
             std::span<const std::uint8_t> free, std::span<const Quat> tet_rot);
  /// Whether the patch in use was made for this structure and this free mask (free: (n)).
  [[nodiscard]] bool patch_fits(std::uint64_t structure, std::span<const std::uint8_t> free) const;
  [[nodiscard]] bool has_patch() const { return m_patch != nullptr; }
  /// Whether node i's rows are solved by the patch.
  [[nodiscard]] bool patched(std::size_t node) const { return in_patch(node); }
  /// The tets' rotations at the patch's step ((m) of its structure; the patch is not warped).
  [[nodiscard]] std::span<const Quat> patch_rotations() const { return m_b->patch.tet_rot; }
  /// Drops the patch (the installed factor fits the matrix again).
  void drop_patch();
  /// The most rows any factor it holds (installed, pending, patch) applies to: a restored
  /// schedule must fit the mesh (3 x its nodes).
  [[nodiscard]] std::int64_t rows_needed() const;
  /// Drops every factor and waits for any running job (the mesh was rebuilt from scratch).
  void clear();

  /// After a cut: the tets' rotations of the installed factor and of the pending refresh follow
  /// the delta's relabels (fem/implicit_integrator.h update()); added tets have none (zero).
  /// tets: the mesh's tet count after it.
  void relabel_tets(const TopologyDelta& delta, std::size_t tets);
  /// The tets' rotations at the installed factor's step ((m) of its structure; empty if none).
  [[nodiscard]] std::span<const Quat> tet_rotations() const { return m_b->installed.tet_rot; }
  /// The nodes' rotations then ((rows / 3)).
  [[nodiscard]] std::span<const Quat> node_rotations() const { return m_b->installed.node_rot; }

  /// The turn of each node since the installed factor's step: warp[i] = R_i R0_i^T for the
  /// factor's nodes, the identity beyond. node_rot: (n) the nodes' rotations now; warp: (n) out.
  void warp(std::span<const Quat> node_rot, std::span<Mat3> warp) const;
  /// z = P^{-1} r = W F^{-1} W^T r on the factor's rows, inv_diag .* r beyond; rows of
  /// constrained nodes (free[i] = 0; their rows of A are diagonal) get inv_diag .* r too and are
  /// kept out of the factor's solve, so a node held or fixed since the refresh costs CG a few
  /// iterations, not hundreds; rows of the patch's nodes get the patch's solve and are kept out of
  /// the factor's too. r, z, inv_diag: (3n), 3n >= rows(); free, warp: (n).
  void apply(std::span<const double> r, std::span<double> z, std::span<const double> inv_diag,
             std::span<const std::uint8_t> free, std::span<const Mat3> warp);

  /// Its schedule is `b` (a block of the state: the matrices of the installed factor, of the
  /// pending refresh and of the patch with their rotations, free masks, structures and install
  /// step) from now on.
  void bind(LaggedBlock& b) noexcept { m_b.bind(b); }
  /// The bound schedule was restored: factors its matrices again (CHOLMOD gives the same bits for
  /// the same matrix); the pending refresh in the background or now (`background`), to be
  /// installed at its step as before. False when a matrix is not SPD.
  bool adopt(bool background);

  [[nodiscard]] bool ready() const { return m_installed != nullptr; }
  [[nodiscard]] bool pending() const { return m_job != nullptr; }
  /// Rows of the installed factor (0 when none).
  [[nodiscard]] std::int32_t rows() const { return ready() ? m_installed_rows : 0; }
  /// Structure the installed factor was computed for.
  [[nodiscard]] std::uint64_t structure() const { return m_b->installed.structure; }
  /// Refreshes installed so far (factor_now included).
  [[nodiscard]] std::uint64_t refreshes() const { return m_b->refreshes; }

 private:
  struct Job {
    CsrMatrix a;
    std::uint64_t structure = 0;
    std::uint64_t ready_step = 0;
    std::unique_ptr<CholmodSolver> solver;
    LdlFactor ldl;          // the factor as exported, kept for its buffers
    BlockFactor blocks;     // its 3x3 float blocks (fem/block_factor.h), empty if not node-blocked
    bool analyzed = false;  // solver already holds the analysis of a's pattern
    // Else the installed factor, when it is of a's pattern: its analysis is copied (only read
    // meanwhile: install() and clear() join the job first).
    const CholmodSolver* analysis_of = nullptr;
    bool ok = false;
    std::thread thread;
  };
  static void run(Job& job);
  void install();  // joins the job and installs its factor if it succeeded
  std::unique_ptr<CholmodSolver> take_spare(std::uint64_t structure, bool& analyzed);

  std::unique_ptr<Job> new_job(const CsrMatrix& a, std::uint64_t structure);
  /// The pending refresh's record in the state (what a restore factors again).
  void record_pending(const CsrMatrix& a, std::uint64_t structure, std::uint64_t ready_step,
                      std::span<const Quat> node_rot, std::span<const Quat> tet_rot,
                      std::span<const std::uint8_t> free);

  std::unique_ptr<Job> m_job;
  double m_last_wait_ms = 0.0;      // see last_wait_ms()
  std::unique_ptr<Job> m_recycled;  // the last job done, its buffers kept for the next
  std::unique_ptr<CholmodSolver> m_installed;
  BlockFactor m_installed_blocks;  // the installed factor's solves (empty: CHOLMOD's)
  std::int32_t m_installed_rows = 0;
  // The factor replaced at the last install, kept with its analysis for the next refresh of the
  // same pattern (a numeric refactorization skips the symbolic analysis).
  std::unique_ptr<CholmodSolver> m_spare;
  std::uint64_t m_spare_structure = 0;
  std::vector<double> m_r, m_z;  // (rows()) the turned, filtered residual and its solve
  // The patch after a cut: a factor of A restricted to the rows of m_b->patch.nodes.
  std::unique_ptr<CholmodSolver> m_patch;
  std::vector<std::int32_t> m_patch_index;    // node -> index in the patch's nodes, or -1
  std::vector<double> m_pr, m_pz, m_w, m_ty;  // (3 patch nodes) patch-sized work vectors
  std::vector<double> m_ru;                   // (3n) r_U - A_UT w
  BoundBlock<LaggedBlock> m_b;                // the schedule: its block of the state
  bool install_patch(CsrMatrix tt, CsrMatrix tu, std::vector<std::int32_t> nodes,
                     std::uint64_t structure, std::vector<std::uint8_t> free,
                     std::vector<Quat> tet_rot);
  void patch_solve(std::span<const double> r, std::span<const std::uint8_t> free,
                   std::vector<double>& w);
  void multiply_ut(std::span<const double> w, double s, std::span<double> out) const;
  void factor_solve(std::span<const double> r, std::span<double> z,
                    std::span<const double> inv_diag, std::span<const std::uint8_t> free,
                    std::span<const Mat3> warp);
  [[nodiscard]] bool in_patch(std::size_t node) const {
    return m_patch && node < m_patch_index.size() && m_patch_index[node] >= 0;
  }
};

}  // namespace serosa::fem
