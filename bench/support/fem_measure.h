// Measurement helpers shared by the FEM benchmarks (bench/fem) and `serosa bench fem`
// (bench/suite/part_fem.cpp), so that both measure accuracy and time the same way: a structured
// bar of Kuhn-subdivided cubes, a timed run of implicit steps, the displacement error against a
// reference run, and the sag of a free end.
#pragma once

#include "engine/tet_mesh.h"
#include "fem/fem_config.h"

namespace serosa::bench {

/// A bar [0, lx] x [-ly/2, ly/2] x [-lz/2, lz/2] (m) of nx x ny x nz boxes, each cut into 6
/// positively oriented tets around its main diagonal (conforming), group 1; node state filled,
/// every node at x = 0 fixed. 6 nx ny nz tets.
[[nodiscard]] TetMesh structured_bar(int nx, int ny, int nz, double lx, double ly, double lz);

/// What a timed run of steps measured.
struct TimedRun {
  double ms_per_step = 0.0;  ///< mean wall time of ImplicitIntegrator::step, ms
  int not_converged = 0;     ///< steps whose solver stopped at its cap or failed
  int rejected = 0;          ///< steps not applied (non-finite result)
};

/// Runs `steps` steps of dt_s (s) on `mesh` (in place) with a fresh ImplicitIntegrator(cfg),
/// timing each step (the first one includes any factorization). With pcg_cholmod the factor is
/// computed on the first step, not in the background, so that its cost is counted.
TimedRun run_timed_steps(TetMesh& mesh, fem::FemConfig cfg, int steps, double dt_s);

/// max_i |x_i - ref.x_i| / max_i |ref.x_i - ref.rest_i|: the displacement error relative to the
/// reference run's largest displacement (1). Same mesh topology required.
[[nodiscard]] double relative_displacement_error(const TetMesh& m, const TetMesh& ref);

/// Mean downward (-y) displacement of the nodes at rest x >= x_end - 1e-6 m, m.
[[nodiscard]] double free_end_sag(const TetMesh& m, double x_end);

}  // namespace serosa::bench
