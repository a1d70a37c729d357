// FemConfig: the read-only FEM model a scene describes (materials per group, solver settings,
// gravity). Plain structs: app maps the scene (engine/scene/scene.h) onto them; fem never reads
// TOML.
#pragma once

#include <cstdint>
#include <map>

#include "engine/math.h"

namespace serosa::fem {

/// Isotropic linear-elastic material of one mesh group, with Rayleigh damping.
struct FemMaterial {
  double young_pa = 3.0e3;         ///< Young's modulus E, Pa
  double poisson = 0.45;           ///< Poisson ratio nu, in (-1, 0.5)
  double density_kgpm3 = 1.0e3;    ///< mass density rho, kg/m^3
  double damping_mass = 0.0;       ///< Rayleigh alpha, 1/s:  C = alpha M + beta K
  double damping_stiffness = 0.0;  ///< Rayleigh beta, s

  /// First Lamé parameter lambda = E nu / ((1 + nu)(1 - 2 nu)), Pa.
  [[nodiscard]] double lame_lambda() const {
    return young_pa * poisson / ((1.0 + poisson) * (1.0 - 2.0 * poisson));
  }
  /// Shear modulus mu = E / (2 (1 + nu)), Pa.
  [[nodiscard]] double lame_mu() const { return young_pa / (2.0 * (1.0 + poisson)); }
};

enum class SolverKind : std::uint8_t {
  pcg,          ///< conjugate gradient, Jacobi preconditioned, OpenMP
  cholmod,      ///< CHOLMOD supernodal Cholesky, numeric factorization every step
  pcg_cholmod,  ///< CG preconditioned by a CHOLMOD factor of the rest-state system, factored in
                ///< a background thread after each topology change (Jacobi until ready)
  pcg_lagged,   ///< CG preconditioned by a CHOLMOD factor of a recent step's system matrix,
                ///< refreshed in the background on a deterministic schedule (fem/lagged_factor.h)
};

/// Linear solver settings of the implicit step.
struct SolverSettings {
  SolverKind kind = SolverKind::pcg;
  double tolerance = 1e-6;   ///< CG: stop when ||r|| <= tolerance * ||b|| (relative residual)
  int max_iterations = 100;  ///< CG iteration cap; the step reports converged = false past it
  bool warm_start = true;    ///< CG: start from the previous step's dv instead of 0
  /// CG: apply A per tet without assembling it (fem/system_matrix.h SystemOperator) instead of
  /// filling the CSR matrix every step. CHOLMOD always assembles; pcg_lagged assembles only on
  /// the steps that factor or patch. Off by default: assembled CG at tens of iterations measured
  /// faster (docs/BENCHMARKS.md "FEM"); scenes turn it on for pcg_lagged (app/compose.cpp), whose
  /// 1-3 iterations a step do not pay for the fill.
  bool matrix_free = false;
  /// CG on the assembled matrix: store its 3x3 blocks in float instead of double (sums stay in
  /// double; fem/block_system.h). Halves the SpMV's memory traffic; the stored entries are
  /// rounded to a relative 6e-8, which perturbs the solution far below CG tolerances >= 1e-6
  /// (docs/BENCHMARKS.md "FEM" measures it). Off by default; CHOLMOD always uses double.
  bool float_matrix = false;
  /// Divergence guard: when the previous step gained energy (StepStatus::energy_gain: a capped
  /// CG on a sliver-laden cut mesh can inject energy, step after step, and grow without bound),
  /// take the gain back out of the kinetic energy before this step: every velocity scaled by
  /// sqrt(1 - gain / E_kin) (to zero at most). Only flagged steps are touched; a converged solve
  /// never flags. Off by default here: positions or velocities set between steps also count as
  /// a gain unless restart_energy_balance() is called, and would be damped away. The app turns
  /// it on (app/compose.cpp): its grasper reports the nodes it moves
  /// (FemStage::nodes_moved_by_caller).
  bool remove_energy_gain = false;
  /// pcg_cholmod, pcg_lagged: factor in a background thread (true) or on the step that needs it
  /// (false; pcg_lagged then gives the same bits either way).
  bool background_factor = true;
  /// pcg_cholmod: the background factorization starts this many ms late. For tests that need
  /// "the factor is not ready yet" deterministically; 0 otherwise.
  int factor_delay_ms = 0;
  /// OpenMP threads of the parallel loops on the thread that steps the FEM stage (FemStage sets
  /// them before each step; they also hold for the later stages on that thread); 0 leaves
  /// OpenMP's own setting.
  int threads = 0;
  /// pcg_lagged: a solve that needed more CG iterations than this asks for a refreshed factor of
  /// its own matrix. Lower: more factorizations (background CPU), fewer iterations per step.
  int refresh_iterations = 2;
  /// pcg_lagged: a refresh asked for at step k preconditions from step k + this on (the
  /// background thread has that many steps to factor; the step waits if it has not finished).
  int factor_lag_steps = 12;
  /// pcg_lagged, after a cut: patch the installed factor with a factor of the rows the cut touched
  /// until a refresh of the new structure is installed (true), or factor the whole new matrix on
  /// the step after the cut (false). The same tolerance either way: this trades the cut step's
  /// time against CG iterations over the next factor_lag_steps steps (fem/lagged_factor.h).
  bool patch_after_cut = true;
  /// pcg_lagged: the lag (steps) of an urgent refresh, one asked for by a solve that needed more
  /// than 3 x refresh_iterations (a grasp, a sudden turn). Such solves cost several times a
  /// normal one, so the sooner the cheaper, as long as the background thread finishes in time
  /// (the step waits for it otherwise). A refresh after a cut is not urgent: the patch bridges it.
  int urgent_lag_steps = 6;
  /// pcg_lagged: the lag (steps) of the refresh after a cut, when more than factor_lag_steps. Its
  /// factorization needs a new symbolic analysis as well, so it takes longer in the background
  /// (about 20 ms for the default scene, against 12 steps of about 1.3 ms: the install step
  /// waited); the patch bridges the lag at a few CG iterations a step.
  int cut_lag_steps = 20;
  /// pcg_lagged: rings of neighbours added around the changed nodes (a cut's, a grasp's) in the
  /// patch. More: a larger patch to factor on the step of the change, fewer CG iterations until
  /// the refresh (the default scene, a cut: 10 a step with 1 ring, 8 with 2, 6 with 3; a grasp:
  /// 10, 7-8, 6-7).
  int patch_rings = 2;
  /// pcg_lagged: a node whose tets turned otherwise than the node itself since the installed
  /// factor's step, by more than this angle, gets its rows patched on this step like a cut's
  /// (fem/lagged_factor.h, misfit), rad; 0: never. The factor turned by the node's warp fits while
  /// the tets around the node turn with it, not while one inverts or a fresh sliver spins.
  double misfit_rad = 0.2;
};

/// Plastic flow (Müller & Gross 2004, section 5), the "plasticity" effect. Per tet, the plastic
/// strain eps_p (symmetric 3x3) is subtracted from the corotated strain before the stress:
/// sigma(sym(R^T F) - I - eps_p). After each step, with the elastic strain
/// eps_e = sym(R^T F) - I - eps_p: if |eps_e|_F > yield, eps_p += min(dt creep, 1) eps_e; then if
/// |eps_p|_F > max, eps_p is scaled back to norm max.
struct PlasticitySettings {
  bool on = false;           ///< the scene lists the "plasticity" effect
  double yield = 0.05;       ///< elastic limit, Frobenius norm of the elastic strain (1)
  double creep_per_s = 0.5;  ///< creep rate, 1/s
  double max = 0.3;          ///< cap on the plastic strain's Frobenius norm (1)
};

/// The whole FEM model. Const after the stage is built.
struct FemConfig {
  std::map<std::uint16_t, FemMaterial> materials;  ///< per group (Gmsh physical tag)
  FemMaterial default_material;                    ///< for groups not in `materials`
  SolverSettings solver;
  PlasticitySettings plasticity;  ///< `on`, and the parameters of groups not in plasticity_groups
  /// Per group (Gmsh physical tag): yield, creep and max of that group's tissue (`on` is ignored).
  std::map<std::uint16_t, PlasticitySettings> plasticity_groups;
  /// Corotational FEM (true: R_e from each tet's deformation gradient, Müller & Gross 2004) or
  /// linear FEM (false: R_e = I, small-strain; rotations show as spurious growth). Linear is for
  /// comparison only (`serosa bench fem`); scenes never set it.
  bool corotational = true;
  bool gravity_on = true;                     ///< the "gravity" effect
  Vec3 gravity_mps2 = Vec3(0.0, -9.81, 0.0);  ///< gravitational acceleration g, m/s^2

  /// The plastic-flow parameters of group g.
  [[nodiscard]] const PlasticitySettings& plasticity_of(std::uint16_t g) const {
    const auto it = plasticity_groups.find(g);
    return it == plasticity_groups.end() ? plasticity : it->second;
  }
  /// The material of group g.
  [[nodiscard]] const FemMaterial& material(std::uint16_t g) const {
    const auto it = materials.find(g);
    return it == materials.end() ? default_material : it->second;
  }
};

}  // namespace serosa::fem
