// Incremental FEM update from TopologyDeltas (fem/fem_elements.h update_elements,
// ImplicitIntegrator::update) equals a full rebuild after random deltas.
#include <gtest/gtest.h>

#include <algorithm>
#include <random>
#include <set>
#include <vector>

#include "engine/topology_delta.h"
#include "fem/fem_elements.h"
#include "fem/implicit_integrator.h"
#include "fem_fixtures.h"

namespace serosa::fem {
namespace {

// A random delta: removes a few tets; each removed tet is either dropped (holes get filled by
// moves) or split into 4 around a new centroid node (parents = its 4 nodes, weights 1/4).
TopologyDelta random_delta(const TetMesh& m, std::mt19937& rng) {
  TopologyDelta d;
  std::uniform_int_distribution<int> tet(0, m.num_tets() - 1);
  std::uniform_int_distribution<int> count(1, 6);
  std::set<std::int32_t> removed;
  const int k = count(rng);
  while (static_cast<int>(removed.size()) < k) removed.insert(tet(rng));
  d.removed_tets.assign(removed.begin(), removed.end());
  std::bernoulli_distribution split(0.6);
  for (std::int32_t t : d.removed_tets) {
    if (!split(rng)) continue;
    const Tet& n = m.tets[static_cast<std::size_t>(t)];
    NodeParent p;
    p.count = 4;
    p.nodes = n;
    p.weights = {0.25, 0.25, 0.25, 0.25};
    const auto c =
        static_cast<std::int32_t>(m.num_nodes() + static_cast<int>(d.added_nodes.size()));
    d.added_nodes.push_back(p);
    const std::uint16_t g = m.group[static_cast<std::size_t>(t)];
    for (int i = 0; i < 4; ++i) {
      Tet s = n;
      s[static_cast<std::size_t>(i)] = c;
      d.added_tets.push_back(s);
      d.added_groups.push_back(g);
    }
  }
  return d;
}

FemConfig two_materials() {
  FemConfig c;
  c.materials[1] = FemMaterial{2e4, 0.4, 1100.0, 0.2, 0.01};
  c.materials[2] = FemMaterial{5e4, 0.3, 900.0, 0.1, 0.02};
  c.solver.kind = SolverKind::cholmod;
  return c;
}

TEST(TopologyUpdate, IncrementalEqualsFullRebuildAfterRandomDeltas) {
  std::mt19937 rng(2024);
  TetMesh mesh = fixtures::grid(6, 3, 3, 0.02, 0.02, 0.02);
  for (std::size_t t = 0; t < mesh.tets.size(); ++t)
    mesh.group[t] = static_cast<std::uint16_t>(1 + t % 2);
  for (std::size_t i = 0; i < mesh.rest.size(); ++i) mesh.fixed[i] = mesh.rest[i].x() < 1e-12;
  const FemConfig cfg = two_materials();
  ImplicitIntegrator inc(cfg);
  ASSERT_TRUE(inc.step(mesh, 0.01).applied);
  int moved = 0;
  for (int round = 0; round < 25; ++round) {
    TopologyDelta d = random_delta(mesh, rng);
    apply(mesh, d);
    moved += static_cast<int>(d.moved_tets.size());
    inc.update(mesh, d);

    FemElements full;
    build_elements(mesh, cfg, full);
    const FemElements& el = inc.elements();
    ASSERT_EQ(el.elements.size(), full.elements.size());
    ASSERT_EQ(el.node_mass.size(), full.node_mass.size());
    for (std::size_t t = 0; t < full.elements.size(); ++t) {
      EXPECT_EQ(el.elements[t].nodes, mesh.tets[t]);
      EXPECT_EQ(el.elements[t].volume_m3, full.elements[t].volume_m3);
      EXPECT_EQ(el.elements[t].lambda_pa, full.elements[t].lambda_pa);
      for (std::size_t a = 0; a < 4; ++a)
        EXPECT_EQ(el.elements[t].grad[a], full.elements[t].grad[a]);
    }
    for (std::size_t i = 0; i < full.node_mass.size(); ++i) {
      EXPECT_NEAR(el.node_mass[i], full.node_mass[i], 1e-12 * (1e-6 + full.node_mass[i])) << i;
      EXPECT_NEAR(el.node_damping[i], full.node_damping[i], 1e-12 * (1e-6 + full.node_mass[i]));
      EXPECT_EQ(mesh.mass[i], el.node_mass[i]);
    }
    // One step from the same state: incremental integrator vs a freshly built one.
    TetMesh copy = mesh;
    ImplicitIntegrator fresh(cfg);
    const StepStatus a = inc.step(mesh, 0.01);
    const StepStatus b = fresh.step(copy, 0.01);
    ASSERT_TRUE(a.applied && b.applied);
    double diff = 0.0;
    for (std::size_t i = 0; i < mesh.x.size(); ++i)
      diff = std::max(diff, (mesh.x[i] - copy.x[i]).norm());
    EXPECT_LE(diff, 1e-10) << "round " << round;
  }
  EXPECT_GT(moved, 0);  // the slot relabelling was exercised
}

}  // namespace
}  // namespace serosa::fem
