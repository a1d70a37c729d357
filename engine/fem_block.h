// The FEM stage's block of the whole state (fem/fem_stage.h, fem/implicit_integrator.h,
// fem/lagged_factor.h): what one implicit step carries to the next that the mesh does not hold.
// Plain data, SI units; (m) per tet, (n) per node. Listed field by field for the snapshot
// (engine/state_walk.h). The factors themselves are not state: CHOLMOD recomputes the same bits
// from the matrices kept here.
#pragma once

#include <cstdint>
#include <vector>

#include "engine/csr_matrix.h"
#include "engine/math.h"

namespace serosa {

/// A matrix the lagged preconditioner factored, with what it was assembled at.
struct FactoredMatrix {
  bool on = false;                 ///< there is one
  CsrMatrix a;                     ///< the matrix (3 x its nodes rows)
  std::vector<Quat> node_rot;      ///< (a.rows / 3) the nodes' rotations then
  std::vector<Quat> tet_rot;       ///< (m) the tets' rotations then
  std::vector<std::uint8_t> free;  ///< (a.rows / 3) 1 where the node took part in the solve
  std::uint64_t structure = 0;     ///< the matrix structure it belongs to
  std::uint64_t ready_step = 0;    ///< a pending refresh: the step it is installed at
  template <class S, class F>
  static void each(S& s, F&& f) {
    f(s.on), f(s.a), f(s.node_rot), f(s.tet_rot), f(s.free), f(s.structure), f(s.ready_step);
  }
};

/// The patch: the rows a cut, a grasp or a release changed, factored on their own.
struct FactorPatch {
  bool on = false;
  CsrMatrix a;                      ///< (3k x 3k) its rows' block of A, patch-local columns
  CsrMatrix tu;                     ///< (3k rows) the rest of its rows, global columns
  std::vector<std::int32_t> nodes;  ///< (k) its nodes, ascending
  std::vector<std::uint8_t> free;   ///< (n) the free mask it was made with
  std::vector<Quat> tet_rot;        ///< (m) the tets' rotations then
  std::uint64_t structure = 0;
  template <class S, class F>
  static void each(S& s, F&& f) {
    f(s.on), f(s.a), f(s.tu), f(s.nodes), f(s.free), f(s.tet_rot), f(s.structure);
  }
};

/// The lagged preconditioner's schedule (solver pcg-lagged).
struct LaggedBlock {
  std::uint64_t refreshes = 0;  ///< refreshes installed so far
  FactoredMatrix installed;     ///< the factor in use
  FactoredMatrix pending;       ///< the refresh being factored, installed at its ready_step
  FactorPatch patch;
  template <class S, class F>
  static void each(S& s, F&& f) {
    f(s.refreshes), f(s.installed), f(s.pending), f(s.patch);
  }
};

struct FemBlock {
  bool stage_built = false;     ///< the stage built its integrator for the mesh
  bool built = false;           ///< the integrator built its elements (the rest is then set)
  std::uint64_t steps = 0;      ///< steps taken (the factor's install schedule)
  std::uint64_t structure = 0;  ///< matrix structures built so far
  std::vector<Quat> q;          ///< (m) per-tet rotation, the next step's warm start
  std::vector<Quat> q_prev;     ///< (m) the rotation a step before (extrapolated start)
  std::vector<double> dv;       ///< (3n) CG's warm start: the last velocity change, m/s
  std::vector<Mat3> plastic;    ///< (m) plastic strain (plasticity on; else empty), 1
  /// (n) lumped alpha M as the cuts left it (sums updated by subtraction, which a rebuild would
  /// round differently), kg/s; the integrator's elements hold the same after every change
  std::vector<double> node_damping;
  double energy_before = 0.0;         ///< the energy guard's balance: energy before the step, J
  double energy_work = 0.0;           ///< and the external work in it, J
  bool energy_pending = false;        ///< the last step's balance is still to be checked
  std::vector<std::uint8_t> changed;  ///< (n) 1: a cut since the installed factor touched it
  LaggedBlock lagged;
  template <class S, class F>
  static void each(S& s, F&& f) {
    f(s.stage_built), f(s.built), f(s.steps), f(s.structure), f(s.q), f(s.q_prev), f(s.dv),
        f(s.plastic), f(s.node_damping), f(s.energy_before), f(s.energy_work), f(s.energy_pending),
        f(s.changed), f(s.lagged);
  }
};

}  // namespace serosa
