// ImplicitIntegrator: one linearized backward-Euler step of corotational FEM (Müller & Gross 2004,
// section 4), with the rotations frozen over the step.
//
// Derivation. Backward Euler on M dv/dt = f_ext + f_el(x) - C v, dx/dt = v:
//   M (v' - v) = dt (f_ext + f_el(x') - C v'),   x' = x + dt v'.
// Linearize the elastic force around x with R fixed: f_el(x') = f_el(x) - K_R (x' - x)
// = f_el(x) - dt K_R v', with K_R = R K R^T (assembled per tet) and f_el(x) = -R K (R^T x - x0).
// Writing v' = v + dv and C = alpha M + beta K_R (Rayleigh):
//   (M + dt C + dt^2 K_R) dv = dt (f_ext + f_el(x) - C v - dt K_R v)
//                            = dt (f_ext - alpha M v + f_el(x) - (beta + dt) K_R v)
// The right-hand side's last two terms are one stress evaluation per tet (elastic_forces.h,
// k_v = beta + dt). Then v' = v + dv and x' = x + dt v'. Fixed nodes keep v = 0 and their x.
//
// Solvers (FemConfig::solver.kind): Jacobi PCG on the assembled matrix (warm-started from the
// previous dv); CHOLMOD (symbolic analysis once per topology version, numeric factorization
// every step); or PCG preconditioned by a CHOLMOD factor of the rest-state matrix
// M + dt C + dt^2 K (R = I), factored once per topology version and dt in a background thread
// (fem/background_factor.h): steps never wait for it (Jacobi until it is ready). A step
// whose solution is not finite, or diverged (the quadratic phi(dv) = dv^T A dv / 2 - b^T dv it
// minimizes is above phi(0) = 0), is not applied: the mesh is left untouched and the status says
// so. An unconverged but finite and reduced CG result (iteration cap reached) is applied and
// reported as converged = false: capping iterations is how real-time runs trade accuracy.
#pragma once

#include <cmath>
#include <cstdint>
#include <span>
#include <vector>

#include "engine/bound_block.h"
#include "engine/fem_block.h"
#include "engine/tet_mesh.h"
#include "engine/topology_delta.h"
#include "fem/background_factor.h"
#include "fem/block_system.h"
#include "fem/cholmod_solver.h"
#include "fem/csr_matrix.h"
#include "fem/fem_config.h"
#include "fem/fem_elements.h"
#include "fem/lagged_factor.h"
#include "fem/pcg.h"
#include "fem/system_matrix.h"

namespace serosa::fem {

struct StepStatus {
  bool converged = false;  ///< the linear solve reached its tolerance (false too on energy_gain)
  /// The linear solve itself reached its tolerance (energy_gain alone does not clear it)
  bool solve_converged = false;
  bool applied = false;   ///< the state was advanced (false: left unchanged, see `converged`)
  int iterations = 0;     ///< CG iterations (0 for CHOLMOD)
  double residual = 0.0;  ///< relative residual ||b - A dv|| / ||b|| of the linear solve
  int inverted_tets = 0;  ///< tets with det F <= 0 at the start of the step
  /// Tets whose rotation turned by more than kTurnedRad since the last step: tissue in flux (a
  /// cut's fresh pieces recoiling), whose matrix a lagged factor would not fit for long.
  int turned_tets = 0;
  /// pcg_cholmod: the rest-state factor for this topology was not ready yet (being computed in
  /// the background), so CG ran with Jacobi instead; the step did not wait.
  bool factor_pending = false;
  /// Divergence guard (energy), for the PREVIOUS step (the result this step started from; its
  /// rotations are extracted here anyway, so the check is free): its mechanical energy (kinetic +
  /// corotated elastic) rose by more than the work of the external forces and gravity over it,
  /// beyond kEnergyGainTolerance of the energies involved. Backward Euler with Rayleigh damping
  /// only dissipates, so a gain means that step's (capped) solve injected energy; slow growth
  /// over a long run with a low iteration cap is how it shows. This step then reports
  /// converged = false and starts its CG cold (not from the previous dv). Not checked across a
  /// topology change (update(), rebuild()) or on the first step; x or v set by the caller between
  /// steps count as a gain unless restart_energy_balance() is called.
  bool energy_gain = false;
  /// Residual guard: the linear solve ended with ||b - A dv|| > ||b|| (worse than dv = 0 in the
  /// residual norm, though its quadratic decreased): converged = false and this flag.
  bool residual_growth = false;
  double energy_j = 0.0;  ///< mechanical energy at the start of this step (as above), J
  /// Kinetic energy taken out before this step (SolverSettings::remove_energy_gain), J.
  double energy_removed_j = 0.0;
  /// energy_j - (energy at the start of the previous step + the external work over it), J.
  double energy_change_j = 0.0;
  /// pcg_lagged: a refreshed factor of the system matrix was asked for after this step's solve
  /// (or, on the first step, computed before it).
  bool factor_refresh = false;
  /// pcg_lagged: the rows a cut, a grasp or a release changed since the installed factor got a
  /// factor of their own this step.
  bool factor_patch = false;
  /// pcg_lagged: wall time this step waited for the background thread to finish the refresh it
  /// installed, ms (0 when it was ready; LaggedFactor::last_wait_ms). The machine's, not the
  /// model's: a replay may wait otherwise and give the same bits.
  double factor_wait_ms = 0.0;
};

/// A tet's rotation turned by more than this in one step counts in StepStatus::turned_tets, rad.
inline constexpr double kTurnedRad = 0.3;
/// cos(kTurnedRad / 2): the bound on |q_last . q| (unit quaternions) of a tet not turned.
inline const double kTurnedCosHalf = std::cos(0.5 * kTurnedRad);

/// Relative tolerance of StepStatus::energy_gain: gain > tol * (E_before + E_after + |W_ext|)
/// + the floor below.
inline constexpr double kEnergyGainTolerance = 1e-4;
/// Floor of StepStatus::energy_gain: gains under the elastic energy of the whole mesh at this
/// uniform strain, 1/2 sum (lambda + 2 mu) V eps^2, are not flagged. Near rest every energy is
/// rounding noise (a beam at rest "gained" 9e-34 J of 1e-32 J), and a real divergence grows
/// past this floor within a few steps.
inline constexpr double kEnergyFloorStrain = 1e-8;

class ImplicitIntegrator {
 public:
  explicit ImplicitIntegrator(FemConfig config);

  /// Full precompute for the mesh: elements, lumped masses (also written to mesh.mass), matrix
  /// pattern, CHOLMOD analysis, rotations from scratch.
  void rebuild(TetMesh& mesh);
  /// rebuild(), and for pcg_lagged the factor of the matrix the next step (of length dt_s) will
  /// assemble, so that step does not factor it: what the first step of a run would do, done at
  /// load time. The warm starts are left as they were: the next step gives the same bits with or
  /// without it.
  void prepare(TetMesh& mesh, double dt_s);
  /// Incremental update after apply(mesh, delta): recomputes only the added elements and the
  /// masses of touched nodes, relabels per-tet rotations, and patches the matrix pattern locally
  /// (fem/system_matrix.h update_pattern). Cost follows the tets touched, not the mesh size,
  /// except for CHOLMOD's symbolic analysis (solver.kind = cholmod: a direct factor is global).
  /// Falls back to rebuild() if nothing was built yet or the delta does not follow the version
  /// this integrator holds.
  void update(TetMesh& mesh, const TopologyDelta& delta);

  /// Advances mesh.x and mesh.v by dt_s. f_ext: (n) external node forces, N, or empty. Gravity
  /// (config) is added to it. Rebuilds first if the mesh's topology_version changed unseen.
  StepStatus step(TetMesh& mesh, double dt_s, std::span<const Vec3> f_ext = {});

  /// Forget the last step's energy balance (StepStatus::energy_gain): call after setting x or v
  /// by hand (initial conditions, a teleported node), which the next step would flag as a gain.
  void restart_energy_balance() { m_b->energy_pending = false; }

  /// pcg_cholmod: blocks until the background factorization (if any) is done. Tests and shutdown
  /// only; steps never call it.
  void wait_for_background() { m_factor.wait(); }

  /// What a step carries to the next that the mesh does not hold is `b`, a block of the state
  /// (engine/fem_block.h: the rotations that warm-start it, CG's warm start, plastic strain, the
  /// damping as the cuts left it, the energy guard's balance and the lagged factor's schedule),
  /// from now on. Without a bind (a test, a benchmark) the integrator keeps its own.
  void bind(FemBlock& b) noexcept {
    m_b.bind(b);
    m_lagged.bind(b.lagged);
  }
  /// The bound block and `mesh` were restored: rebuilds the caches for them (elements, pattern,
  /// factors), keeping the restored masses, and continues the run bit for bit. Throws
  /// BlockMismatch when the block does not fit the mesh.
  void adopt(TetMesh& mesh);
  [[nodiscard]] const FemConfig& config() const { return m_config; }
  /// (m) per-tet plastic strain (plasticity on; empty before the first step or when off).
  [[nodiscard]] std::span<const Mat3> plastic_strain() const { return m_b->plastic; }
  [[nodiscard]] const FemElements& elements() const { return m_el; }
  [[nodiscard]] std::span<const Mat3> rotations() const { return m_rot; }
  /// The matrix pattern (CSR); its values hold A only for solver.kind = cholmod (CG fills the
  /// block storage instead, fem/block_system.h): see assembled_matrix().
  [[nodiscard]] const CsrMatrix& matrix() const { return m_a; }
  /// A of the last step as a CSR matrix, whichever storage the solver filled (a copy; tests).
  [[nodiscard]] CsrMatrix assembled_matrix() const;
  [[nodiscard]] const SystemPattern& pattern() const { return m_pattern; }
  /// What the last update() did to the matrix pattern.
  [[nodiscard]] const PatternUpdateStats& last_update() const { return m_last_update; }

 private:
  /// What the per-tet pass of a step sums up.
  struct ElementPass {
    int inverted = 0;               ///< tets with det F <= 0
    int turned = 0;                 ///< tets turned by more than kTurnedRad since the last step
    double elastic_j = 0.0;         ///< corotated elastic energy at x, J
    double stiffness_volume = 0.0;  ///< sum of (lambda + 2 mu) V over active tets, J
  };
  /// The linear operator of this step's solve (one of the two is set).
  struct SystemProduct {
    MatVec apply;         ///< y = A x
    MatVecDot apply_dot;  ///< y = A x, returning x . y
  };

  void rebuild_solver_structure(const TetMesh& mesh);
  void reserve_for_cuts(TetMesh& mesh);
  void update_plasticity(const TetMesh& mesh, double dt_s);
  /// step(); `may_remove`: the energy gain of the previous step may be taken out (then the
  /// step runs again from the slowed state, once).
  StepStatus step_from(TetMesh& mesh, double dt_s, std::span<const Vec3> f_ext, bool may_remove);
  /// Per tet: rotation (warm-started), rotated gradients, stiffness scales and the corner forces
  /// f_el(x) - (beta + dt) K_R v of the right-hand side (m_fe).
  ElementPass element_pass(const TetMesh& mesh, double dt_s);
  /// b (m_rhs) = dt (f_ext + m g - c v + sum of corner forces), 0 on constrained nodes; returns
  /// the kinetic energy of the free nodes, J.
  double assemble_rhs(const TetMesh& mesh, double dt_s, std::span<const Vec3> f_ext);
  /// The divergence guard's check of the previous step (StepStatus::energy_gain).
  void check_energy_balance(const ElementPass& pass, double kinetic_j, StepStatus& st);
  /// Fills A for the solver kind and returns its product.
  SystemProduct assemble_system(const TetMesh& mesh, double dt_s);
  /// Solves A dv = b with the configured solver (the linear-solver strategy).
  SolveStatus solve_system(const TetMesh& mesh, double dt_s, const SystemProduct& a,
                           StepStatus& st);
  SolveStatus solve_direct(const SystemProduct& a);
  SolveStatus solve_cg(const TetMesh& mesh, double dt_s, const SystemProduct& a, StepStatus& st);
  /// The preconditioner of solve_cg (a CHOLMOD factor, or Jacobi when it leaves apply empty).
  Preconditioner cg_preconditioner(const TetMesh& mesh, double dt_s, StepStatus& st);
  /// pcg_lagged after the solve: asks for a refreshed factor when CG needed too many iterations
  /// or the structure changed.
  void schedule_refresh(const TetMesh& mesh, double dt_s, int iterations, StepStatus& st);
  /// m_free from the mesh's Dirichlet flags and masses.
  void update_free_mask(const TetMesh& mesh);
  /// m_node_rot from this step's element rotations (fem/lagged_factor.h, warping).
  void update_node_rotations(const TetMesh& mesh);
  /// pcg_lagged's part of cg_preconditioner: the install schedule, the patch after a cut, a grasp
  /// or a release.
  void lagged_preconditioner(const TetMesh& mesh, double dt_s, StepStatus& st,
                             Preconditioner& precond);
  /// What no longer fits the preconditioner: nodes the factor's warp does not fit plus the patch's
  /// tets that turned since it was made (nodes), and of those the nodes outside the patch plus
  /// the same tets (unpatched: a patch that no longer fits itself is made anew).
  struct Misfit {
    int nodes = 0;
    int unpatched = 0;
  };
  /// Marks in m_kind_changed the nodes the installed factor's warp no longer fits (a tet of theirs
  /// turned otherwise than they did since its step, SolverSettings::misfit_rad), and those of the
  /// patch's tets that turned since the patch was made.
  Misfit mark_misfit_nodes(const TetMesh& mesh);
  /// Its two parts: the patch's nodes and the factor's; cos_half: cos(misfit_rad / 2).
  int mark_patch_misfit(const TetMesh& mesh, double cos_half);
  Misfit mark_factor_misfit(const TetMesh& mesh, double cos_half);
  /// Patches the lagged factor with the rows of m_kind_changed and their rings (factors the whole
  /// matrix instead if that submatrix is not SPD).
  void patch_lagged_factor(const TetMesh& mesh, double dt_s, StepStatus& st);
  /// This step's A in m_a for the lagged factor (the blocks filled if the product did not).
  const CsrMatrix& lagged_csr(const TetMesh& mesh, double dt_s);
  /// m_a with at least the rows of m_patch_nodes filled for this step (all of them when the
  /// blocks are already fresh).
  const CsrMatrix& patch_rows_csr(const TetMesh& mesh, double dt_s);
  /// Jacobi's inverse diagonal of this step's A, into m_pcg.inv_diag.
  void fill_inverse_diagonal();
  /// v' = v + dv, x' = x + dt v' on free nodes; returns the work of gravity and f_ext, J.
  double apply_update(TetMesh& mesh, double dt_s, std::span<const Vec3> f_ext);

  const FemConfig m_config;
  FemElements m_el;
  SystemPattern m_pattern;
  CsrMatrix m_a;                       // (3n x 3n) system matrix (CHOLMOD; pattern for all)
  std::vector<double> m_blocks_d;      // A in 3x3 blocks for CG (fem/block_system.h), double
  bool m_blocks_fresh = false;         // m_blocks_d holds this step's A
  bool m_csr_fresh = false;            // m_a holds a copy of it (pcg_lagged)
  std::vector<float> m_blocks_f;       // the same in float (solver.float_matrix)
  std::vector<double> m_fill_scratch;  // fill_blocks' per-thread row sums (no step allocates)
  std::vector<TetScale> m_scale;       // (m) per-tet stiffness scales of the fill, this step
  std::vector<Mat3> m_rot;             // (m) R_e of the current step
  std::vector<Vec3> m_rg;              // (4m) rotated gradients R_e b_a of the current step, 1/m
  SystemOperator m_op;                 // matrix-free system (solver.matrix_free)
  std::vector<Vec3> m_fe;              // (4m) per-tet corner forces of the right-hand side, N
  std::vector<double> m_rhs;           // (3n) b = dt (...), N s
  PcgScratch m_pcg;
  CholmodSolver m_cholmod;  // cholmod: factor of A
  bool m_analyzed = false;
  // pcg_cholmod: the factor of the rest-state system (R = I), computed in the background for
  // each matrix structure (m_b->structure counts rebuilds of the pattern).
  BackgroundFactor m_factor;
  std::vector<Vec3> m_rg_rest;  // (4m) unrotated gradients b_a
  // pcg_lagged: the factor of a recent step's A (fem/lagged_factor.h), computed from the blocks
  // copied into m_a; m_b->steps counts steps (the factor's install schedule).
  LaggedFactor m_lagged;
  std::vector<std::uint8_t> m_free;  // (n) 1 where the node takes part in the solve
  std::vector<Quat> m_node_rot;      // (n) the nodes' rotations this step (factor warping)
  std::vector<Mat3> m_warp;          // (n) each node's turn since the installed factor's step
  std::vector<Quat> m_node_warp;     // (n) scratch: the same as quaternions (misfit)
  std::vector<std::uint8_t> m_kind_changed;  // (n) scratch: held or let go since the factor
  std::vector<std::uint8_t> m_patch_nodes;   // (n) scratch: the changed nodes and their rings
  std::vector<std::uint8_t> m_ring_inner;    // (n) scratch: the patch before its next ring
  // This step (derived from the state each step, so nothing to save): the patch in use covers a
  // cut, a grasp or a release (not only misfit nodes), and it was made new on this step for one.
  bool m_patch_for_change = false;
  bool m_patch_new = false;
  std::vector<Tet> m_removed;  // scratch of update(): nodes of the removed tets
  PatternUpdateStats m_last_update;
  // Divergence guard: energy at the start of the last step and the external work over it, J.
  BoundBlock<FemBlock> m_b;  // the warm starts, the balance and the schedule: state
};

}  // namespace serosa::fem
