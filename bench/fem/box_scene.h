// The SOFA-matching box of docs/BENCHMARKS.md "FEM" (issue 4): a 4 x 1 x 1 m bar along x, the
// x = 0 face fixed, gravity -9.81 m/s^2 along y, E = 3000 Pa, nu = 0.45, rho = 1 kg/m^3, Rayleigh
// 0.1 (mass, 1/s) and 0.1 (stiffness, s), dt = 0.01 s. Either a structured mesh built here (sizes
// 1k..200k tets in one code path) or the gmsh meshes assets/box_19k.msh and assets/box_95k.msh.
#pragma once

#include <array>
#include <filesystem>
#include <string>

#include "engine/mesh_io.h"
#include "engine/tet_mesh.h"
#include "fem/fem_config.h"

namespace serosa::fem::bench {

inline constexpr double kBoxDt = 0.01;  ///< s

/// Structured 4k x k x k grid of unit-length/k cubes, 6 tets each (Kuhn): 24 k^3 tets.
inline TetMesh structured_box(int k) {
  TetMesh m;
  const int nx = 4 * k, ny = k, nz = k;
  const double h = 1.0 / k;
  const auto id = [&](int i, int j, int l) { return i + (nx + 1) * (j + (ny + 1) * l); };
  for (int l = 0; l <= nz; ++l)
    for (int j = 0; j <= ny; ++j)
      for (int i = 0; i <= nx; ++i) m.add_node(Vec3(i * h, j * h - 0.5, l * h - 0.5));
  static constexpr std::array<std::array<int, 3>, 6> perms{
      {{0, 1, 2}, {0, 2, 1}, {1, 0, 2}, {1, 2, 0}, {2, 0, 1}, {2, 1, 0}}};
  for (int l = 0; l < nz; ++l)
    for (int j = 0; j < ny; ++j)
      for (int i = 0; i < nx; ++i)
        for (const auto& p : perms) {
          std::array<int, 3> c{i, j, l};
          Tet t{};
          t[0] = id(c[0], c[1], c[2]);
          for (std::size_t s = 0; s < 3; ++s) {
            ++c[static_cast<std::size_t>(p[s])];
            t[s + 1] = id(c[0], c[1], c[2]);
          }
          if (signed_volume(m.rest[t[0]], m.rest[t[1]], m.rest[t[2]], m.rest[t[3]]) < 0.0)
            std::swap(t[2], t[3]);
          m.add_tet(t, 1);
        }
  m.fill_node_state();
  for (std::size_t i = 0; i < m.rest.size(); ++i) m.fixed[i] = m.rest[i].x() < 1e-9 ? 1 : 0;
  return m;
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
inline double free_end_sag(const TetMesh& m) {
  double s = 0.0;
  int n = 0;
  for (std::size_t i = 0; i < m.rest.size(); ++i)
    if (m.rest[i].x() > 4.0 - 1e-6) {
      s += m.rest[i].y() - m.x[i].y();
      ++n;
    }
  return n > 0 ? s / n : 0.0;
}

}  // namespace serosa::fem::bench
