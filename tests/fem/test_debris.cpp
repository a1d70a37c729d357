// Debris: a free piece lighter than kDebrisVolumeM3 (the chip two nearly coincident cuts leave)
// is left inactive: massless, its nodes stay where it was cut, whatever the solver's tolerance;
// a piece above it falls like any tissue; a cut that frees a chip gives the same elements and
// masses incrementally as a full rebuild.
#include <gtest/gtest.h>

#include "fem/fem_elements.h"
#include "fem/fem_fixtures.h"
#include "fem/implicit_integrator.h"

namespace serosa::fem {
namespace {

FemConfig soft_pcg() {
  FemConfig c;
  c.default_material = FemMaterial{3000.0, 0.45, 1000.0, 0.1, 0.1};
  c.solver.kind = SolverKind::pcg;
  c.solver.tolerance = 1e-3;  // the organs' tolerance: far too loose for a chip
  c.solver.max_iterations = 200;
  return c;
}

// Appends a Kuhn cube (6 tets) of side `side_m` at `at` to `mesh`; returns its first tet.
std::int32_t add_cube(TetMesh& mesh, const Vec3& at, double side_m) {
  const TetMesh cube = test_meshes::kuhn_bar(1, 1, 1, side_m, side_m, side_m);
  const std::int32_t first_node = mesh.num_nodes(), first_tet = mesh.num_tets();
  for (const Vec3& p : cube.rest) (void)mesh.add_node(at + p);
  for (const Tet& t : cube.tets)
    (void)mesh.add_tet({t[0] + first_node, t[1] + first_node, t[2] + first_node, t[3] + first_node},
                       1);
  return first_tet;
}

// A clamped bar with, beside it, a free chip (0.2 mm cube, 8e-12 m^3) and a free 1 mm cube
// (1e-9 m^3, ten times the threshold).
TetMesh bar_chip_and_cube() {
  TetMesh m = fixtures::clamped_bar(6, 2, 2, 0.01, 0.01, 0.01);
  (void)add_cube(m, Vec3(0.0, 0.05, 0.0), 2e-4);
  (void)add_cube(m, Vec3(0.0, 0.08, 0.0), 1e-3);
  m.fill_node_state();
  return m;
}

TEST(Debris, AFreeChipStaysWhereItWasAndAHeavierPieceFalls) {
  TetMesh mesh = bar_chip_and_cube();
  const TetMesh start = mesh;
  ImplicitIntegrator fem(soft_pcg());
  fem.rebuild(mesh);
  EXPECT_EQ(fem.elements().debris_tets, 6);
  EXPECT_NEAR(fem.elements().debris_volume_m3, 8e-12, 1e-20);
  const std::int32_t chip = 3 * 7 * 3, cube = chip + 8;  // first nodes of each (bar: 7x3x3)
  for (std::int32_t i = chip; i < cube; ++i) EXPECT_EQ(mesh.mass[static_cast<std::size_t>(i)], 0.0);
  for (int s = 0; s < 200; ++s) ASSERT_TRUE(fem.step(mesh, 0.005).applied) << s;
  for (std::int32_t i = 0; i < mesh.num_nodes(); ++i)
    ASSERT_TRUE(mesh.x[static_cast<std::size_t>(i)].allFinite());
  for (std::int32_t i = chip; i < cube; ++i)
    EXPECT_EQ(mesh.x[static_cast<std::size_t>(i)], start.x[static_cast<std::size_t>(i)]) << i;
  // 1 s of free fall: 4.9 m for the cube, within damping
  const double fell =
      start.x[static_cast<std::size_t>(cube)].y() - mesh.x[static_cast<std::size_t>(cube)].y();
  EXPECT_GT(fell, 1.0);
  EXPECT_GT(start.x.back().y() - mesh.x.back().y(), 1.0);
  // the bar sags under gravity as it would without the chip
  EXPECT_LT(mesh.x[static_cast<std::size_t>(chip - 1)].y(),
            start.x[static_cast<std::size_t>(chip - 1)].y());
}

// A cut (here: removing the one tet that joined a chip to the bar) that frees a chip: the
// incremental update finds it as the full rebuild does, with the same masses.
TEST(Debris, AChipACutFreesIsFoundIncrementallyAsByARebuild) {
  TetMesh mesh = fixtures::clamped_bar(6, 2, 2, 0.01, 0.01, 0.01);
  const std::int32_t corner = 0;  // a node of the bar the bridge tet shares
  const std::int32_t chip = add_cube(mesh, mesh.rest[corner] - Vec3(4e-4, 4e-4, 4e-4), 2e-4);
  const std::int32_t a = mesh.tets[static_cast<std::size_t>(chip)][0];
  const std::int32_t b = mesh.tets[static_cast<std::size_t>(chip)][1];
  const std::int32_t c = mesh.tets[static_cast<std::size_t>(chip)][2];
  // the bridge: the chip's face (a, b, c) coned to the bar's corner, oriented positive
  Tet bridge{a, b, c, corner};
  mesh.fill_node_state();
  if ((mesh.rest[b] - mesh.rest[a])
          .cross(mesh.rest[c] - mesh.rest[a])
          .dot(mesh.rest[corner] - mesh.rest[a]) < 0.0)
    std::swap(bridge[1], bridge[2]);
  const std::int32_t bridge_id = mesh.add_tet(bridge, 1);
  mesh.fill_node_state();
  ImplicitIntegrator inc(soft_pcg());
  inc.rebuild(mesh);
  EXPECT_EQ(inc.elements().debris_tets, 0);  // joined to the bar: tissue
  TopologyDelta cut;
  cut.removed_tets = {bridge_id};
  apply(mesh, cut);
  inc.update(mesh, cut);
  EXPECT_EQ(inc.elements().debris_tets, 6);
  FemElements full;
  build_elements(mesh, soft_pcg(), full);
  EXPECT_EQ(full.debris_tets, 6);
  ASSERT_EQ(full.node_mass.size(), inc.elements().node_mass.size());
  for (std::size_t i = 0; i < full.node_mass.size(); ++i)
    EXPECT_NEAR(inc.elements().node_mass[i], full.node_mass[i], 1e-15) << i;
  for (std::size_t t = 0; t < full.elements.size(); ++t)
    EXPECT_EQ(inc.elements().elements[t].active(), full.elements[t].active()) << t;
  for (std::size_t i = 0; i < full.node_mass.size(); ++i)
    EXPECT_EQ(mesh.mass[i], full.node_mass[i]);
}

}  // namespace
}  // namespace serosa::fem
