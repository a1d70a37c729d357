// The SOFA-matching box of docs/BENCHMARKS.md "FEM": a 4 x 1 x 1 m bar along x, the
// x = 0 face fixed, gravity -9.81 m/s^2 along y, E = 3000 Pa, nu = 0.45, rho = 1 kg/m^3, Rayleigh
// 0.1 (mass, 1/s) and 0.1 (stiffness, s), dt = 0.01 s. Either a structured mesh built here (sizes
// 1k..200k tets in one code path) or the gmsh meshes assets/box_19k.msh and assets/box_95k.msh.
#pragma once

#include <filesystem>
#include <string>

#include "bench/support/fem_measure.h"
#include "engine/io/mesh_io.h"
#include "engine/tet_mesh.h"
#include "fem/fem_config.h"

namespace serosa::fem::bench {

inline constexpr double kBoxDt = 0.01;  ///< s

/// Structured 4k x k x k grid of unit-length/k cubes, 6 tets each (Kuhn): 24 k^3 tets.
inline TetMesh structured_box(int k) {
  return serosa::bench::structured_bar(4 * k, k, k, 4.0, 1.0, 1.0);
}

/// assets/<name> (the gmsh boxes), x = 0 fixed.
inline TetMesh asset_box(const std::string& name) {
  TetMesh m = read_mesh(std::filesystem::path(SEROSA_SOURCE_DIR) / "assets" / name);
  m.fill_node_state();
  for (std::size_t i = 0; i < m.rest.size(); ++i) m.fixed[i] = m.rest[i].x() < 1e-6 ? 1 : 0;
  return m;
}

/// The SOFA benchmark's material and damping, with the given solver settings.
inline FemConfig box_config(SolverKind kind, double tolerance, int max_iterations) {
  FemConfig c;
  c.default_material = FemMaterial{3000.0, 0.45, 1.0, 0.1, 0.1};
  c.solver.kind = kind;
  c.solver.tolerance = tolerance;
  c.solver.max_iterations = max_iterations;
  return c;
}

/// Sag of the free end: mean downward displacement of the nodes at x = 4, m.
inline double free_end_sag(const TetMesh& m) { return serosa::bench::free_end_sag(m, 4.0); }

}  // namespace serosa::fem::bench
