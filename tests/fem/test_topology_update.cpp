// Incremental FEM update from TopologyDeltas (fem/fem_elements.h update_elements,
// fem/system_matrix.h update_pattern, ImplicitIntegrator::update) equals a full rebuild after
// random synthetic deltas and after real scissor cuts: elements, masses, a valid matrix pattern,
// the same matrix entry by entry and the same step; and a small cut stays local.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <random>
#include <set>
#include <string>
#include <vector>

#include "engine/topology_delta.h"
#include "fem/fem_elements.h"
#include "fem/implicit_integrator.h"
#include "fem/system_matrix.h"
#include "fem_cuts.h"
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

FemConfig two_materials(SolverKind kind) {
  FemConfig c;
  c.materials[1] = FemMaterial{2e4, 0.4, 1100.0, 0.2, 0.01};
  c.materials[2] = FemMaterial{5e4, 0.3, 900.0, 0.1, 0.02};
  c.solver.kind = kind;
  c.solver.tolerance = 1e-12;
  c.solver.max_iterations = 5000;
  return c;
}

// The pattern is valid: every block start of every tet points into the right row at the right
// column, every diagonal start at (3i, 3i), and the incidence lists are ascending and complete.
void expect_valid_pattern(const TetMesh& mesh, const SystemPattern& p, const CsrMatrix& a) {
  ASSERT_EQ(p.nodes, mesh.num_nodes());
  ASSERT_EQ(a.rows, 3 * mesh.num_nodes());
  ASSERT_EQ(p.block.size(), mesh.tets.size());
  for (std::size_t t = 0; t < mesh.tets.size(); ++t)
    for (std::size_t ca = 0; ca < 4; ++ca)
      for (std::size_t cb = 0; cb < 4; ++cb) {
        const auto row = static_cast<std::size_t>(3 * mesh.tets[t][ca]);
        const std::int32_t k = p.block[t][4 * ca + cb];
        ASSERT_GE(k, a.row_start[row]) << "tet " << t;
        ASSERT_LT(k, a.row_start[row] + a.row_nz[row]) << "tet " << t;
        ASSERT_EQ(a.col[static_cast<std::size_t>(k)], 3 * mesh.tets[t][cb]) << "tet " << t;
      }
  for (std::size_t i = 0; i < static_cast<std::size_t>(p.nodes); ++i) {
    ASSERT_EQ(a.col[static_cast<std::size_t>(p.diag_start[i])], static_cast<std::int32_t>(3 * i));
    const auto inc = p.incident_of(i);
    ASSERT_TRUE(std::is_sorted(inc.begin(), inc.end()));
    for (std::int32_t c : inc)
      ASSERT_EQ(mesh.tets[static_cast<std::size_t>(c / 4)][c % 4], static_cast<std::int32_t>(i));
  }
}

// Same entries row by row: columns exactly, values to `rel` of the largest entry.
void expect_same_matrix(const CsrMatrix& a, const CsrMatrix& b, double rel) {
  ASSERT_EQ(a.rows, b.rows);
  ASSERT_EQ(a.nnz(), b.nnz());
  double scale = 0.0;
  for (double v : b.val) scale = std::max(scale, std::abs(v));
  for (std::size_t r = 0; r < static_cast<std::size_t>(a.rows); ++r) {
    ASSERT_EQ(a.row_nz[r], b.row_nz[r]) << "row " << r;
    for (std::int32_t k = 0; k < a.row_nz[r]; ++k) {
      const auto ka = static_cast<std::size_t>(a.row_start[r] + k);
      const auto kb = static_cast<std::size_t>(b.row_start[r] + k);
      ASSERT_EQ(a.col[ka], b.col[kb]) << "row " << r;
      ASSERT_NEAR(a.val[ka], b.val[kb], rel * scale) << "row " << r << " col " << a.col[ka];
    }
  }
}

// The incrementally updated integrator `inc` on `mesh` equals a full rebuild: elements, masses,
// matrix pattern, and one step (its matrix and the positions it produces).
void expect_equals_rebuild(TetMesh& mesh, ImplicitIntegrator& inc, const FemConfig& cfg,
                           double pos_tol) {
  FemElements full;
  build_elements(mesh, cfg, full);
  const FemElements& el = inc.elements();
  ASSERT_EQ(el.elements.size(), full.elements.size());
  ASSERT_EQ(el.node_mass.size(), full.node_mass.size());
  for (std::size_t t = 0; t < full.elements.size(); ++t) {
    ASSERT_EQ(el.elements[t].nodes, mesh.tets[t]);
    ASSERT_EQ(el.elements[t].volume_m3, full.elements[t].volume_m3);
    ASSERT_EQ(el.elements[t].lambda_pa, full.elements[t].lambda_pa);
    for (std::size_t a = 0; a < 4; ++a) ASSERT_EQ(el.elements[t].grad[a], full.elements[t].grad[a]);
  }
  for (std::size_t i = 0; i < full.node_mass.size(); ++i) {
    ASSERT_NEAR(el.node_mass[i], full.node_mass[i], 1e-12 * (1e-6 + full.node_mass[i])) << i;
    ASSERT_NEAR(el.node_damping[i], full.node_damping[i], 1e-12 * (1e-6 + full.node_mass[i]));
    ASSERT_EQ(mesh.mass[i], el.node_mass[i]);
  }
  expect_valid_pattern(mesh, inc.pattern(), inc.matrix());
  // The patched pattern assembles the same matrix as a fresh one, to round-off (the only
  // difference: the order of the node-mass sums), here with random rotations.
  {
    std::mt19937 rng(9);
    std::vector<Mat3> rot(mesh.tets.size());
    for (Mat3& r : rot) r = fixtures::random_rotation(rng);
    std::vector<Vec3> rg(4 * mesh.tets.size());
    rotated_gradients(full, rot, rg);
    CsrMatrix patched = inc.matrix();
    fill_system(mesh, el, inc.pattern(), rg, 0.01, patched);
    SystemPattern p;
    CsrMatrix a;
    build_pattern(mesh, p, a);
    fill_system(mesh, full, p, rg, 0.01, a);
    expect_same_matrix(patched, a, 1e-14);
    if (::testing::Test::HasFatalFailure()) return;
  }
  // One step from the same state: incremental integrator vs a freshly built one. Both matrices
  // then hold A at that state; they differ by the rotations' tolerance (the incremental one
  // warm-starts each tet's rotation from the last step, the fresh one starts cold; both stop
  // within 1e-7 rad, fem/rotation.h), so values and positions agree to ~1e-8.
  TetMesh copy = mesh;
  ImplicitIntegrator fresh(cfg);
  const StepStatus a = inc.step(mesh, 0.01);
  const StepStatus b = fresh.step(copy, 0.01);
  ASSERT_TRUE(a.applied && b.applied);
  expect_same_matrix(inc.assembled_matrix(), fresh.assembled_matrix(), 1e-7);
  double diff = 0.0, scale = 0.0;
  for (std::size_t i = 0; i < mesh.x.size(); ++i) {
    diff = std::max(diff, (mesh.x[i] - copy.x[i]).norm());
    scale = std::max(scale, (copy.x[i] - copy.rest[i]).norm());
  }
  EXPECT_LE(diff, pos_tol * scale);
}

TetMesh two_group_bar() {
  TetMesh mesh = test_meshes::kuhn_bar(6, 3, 3, 0.02, 0.02, 0.02);
  for (std::size_t t = 0; t < mesh.tets.size(); ++t)
    mesh.group[t] = static_cast<std::uint16_t>(1 + t % 2);
  mesh.fill_node_state();
  fixtures::clamp_x0(mesh);
  return mesh;
}

class TopologyUpdate : public ::testing::TestWithParam<SolverKind> {};

TEST_P(TopologyUpdate, IncrementalEqualsFullRebuildAfterRandomDeltas) {
  std::mt19937 rng(2024);
  TetMesh mesh = two_group_bar();
  const FemConfig cfg = two_materials(GetParam());
  ImplicitIntegrator inc(cfg);
  ASSERT_TRUE(inc.step(mesh, 0.01).applied);
  int moved = 0, compacted = 0;
  for (int round = 0; round < 40; ++round) {
    TopologyDelta d = random_delta(mesh, rng);
    apply(mesh, d);
    moved += static_cast<int>(d.moved_tets.size());
    inc.update(mesh, d);
    compacted += inc.last_update().compacted ? 1 : 0;
    expect_equals_rebuild(mesh, inc, cfg, 1e-6);
    if (HasFatalFailure()) return;
  }
  EXPECT_GT(moved, 0);  // the slot relabelling was exercised
  (void)compacted;
}

// Many deltas on a small mesh: rows keep moving to the end of the storage until the gaps
// outweigh the lists and the storage is compacted; the pattern stays valid throughout and the
// result still equals a full rebuild.
TEST(TopologyUpdateCompaction, StorageIsCompactedAndStaysExact) {
  std::mt19937 rng(31);
  TetMesh mesh = test_meshes::kuhn_bar(3, 2, 2, 0.02, 0.02, 0.02);
  mesh.fill_node_state();
  fixtures::clamp_x0(mesh);
  const FemConfig cfg = two_materials(SolverKind::cholmod);
  ImplicitIntegrator inc(cfg);
  ASSERT_TRUE(inc.step(mesh, 0.01).applied);
  int compacted = 0;
  for (int round = 0; round < 150 && compacted < 2; ++round) {
    TopologyDelta d = random_delta(mesh, rng);
    apply(mesh, d);
    inc.update(mesh, d);
    expect_valid_pattern(mesh, inc.pattern(), inc.matrix());
    if (HasFatalFailure()) return;
    if (inc.last_update().compacted) {
      ++compacted;
      expect_equals_rebuild(mesh, inc, cfg, 1e-6);
      if (HasFatalFailure()) return;
    }
  }
  EXPECT_GT(compacted, 0);
  expect_equals_rebuild(mesh, inc, cfg, 1e-6);
}

// Real scissor cuts (serosa::cutting), small partial blades and complete ones, on a mesh that
// sags under gravity between cuts. With CHOLMOD (exact solves) so that the step comparison is
// not limited by CG's convergence on the slivers cuts make; the pattern and matrix checks are
// solver-independent.
TEST(TopologyUpdateCuts, IncrementalEqualsFullRebuildAfterRealCuts) {
  std::mt19937 rng(77);
  TetMesh mesh = two_group_bar();
  const FemConfig cfg = two_materials(SolverKind::cholmod);
  ImplicitIntegrator inc(cfg);
  for (int s = 0; s < 3; ++s) ASSERT_TRUE(inc.step(mesh, 0.01).applied);
  int cuts = 0;
  for (int round = 0; round < 9; ++round) {
    const double half = round % 3 == 2 ? 1.0 : 0.025;  // complete, else ~1-2 cells wide
    TopologyDelta d = fixtures::random_cut(mesh, half, rng);
    if (d.empty()) continue;
    apply(mesh, d);
    inc.update(mesh, d);
    ++cuts;
    expect_equals_rebuild(mesh, inc, cfg, 1e-6);
    if (HasFatalFailure()) return;
  }
  EXPECT_GE(cuts, 6);
}

INSTANTIATE_TEST_SUITE_P(Solvers, TopologyUpdate,
                         ::testing::Values(SolverKind::cholmod, SolverKind::pcg),
                         [](const ::testing::TestParamInfo<SolverKind>& i) {
                           return std::string(i.param == SolverKind::cholmod ? "cholmod" : "pcg");
                         });

// The update is local: one small cut in a 12k-tet mesh rewrites the rows of a few dozen nodes
// and the blocks of the tets around them, not the mesh.
TEST(TopologyUpdateLocality, SmallCutTouchesOnlyItsNeighbourhood) {
  std::mt19937 rng(5);
  TetMesh mesh = test_meshes::kuhn_bar(40, 7, 7, 0.01, 0.01, 0.01);
  mesh.fill_node_state();
  fixtures::clamp_x0(mesh);
  FemConfig cfg = two_materials(SolverKind::pcg);
  cfg.solver.max_iterations = 20;
  ImplicitIntegrator inc(cfg);
  ASSERT_TRUE(inc.step(mesh, 0.01).applied);
  for (int round = 0; round < 3; ++round) {
    TopologyDelta d = fixtures::random_cut(mesh, 0.012, rng);
    ASSERT_FALSE(d.empty());
    apply(mesh, d);
    inc.update(mesh, d);
    const PatternUpdateStats& st = inc.last_update();
    const auto changed = static_cast<std::int32_t>(d.removed_tets.size() + d.added_tets.size());
    EXPECT_FALSE(st.compacted);
    EXPECT_GT(st.rows_rewritten, 0);
    EXPECT_LE(st.rows_rewritten, st.nodes_touched);
    // Tets around the touched rows: bounded by the cut's size (each node has ~24 tets), not by
    // the mesh (bench/fem/bench_topology.cpp shows the time staying flat from 19k to 165k tets).
    EXPECT_LE(st.blocks_updated, 30 * changed);
    EXPECT_LT(st.blocks_updated, mesh.num_tets() / 4);
    expect_valid_pattern(mesh, inc.pattern(), inc.matrix());
    ASSERT_TRUE(inc.step(mesh, 0.01).applied);
  }
}

}  // namespace
}  // namespace serosa::fem
