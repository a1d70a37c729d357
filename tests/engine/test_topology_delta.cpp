// TopologyDelta::apply: the canonical slot rules every consumer relies on, checked against a
// brute-force model over thousands of random deltas.
#include <gtest/gtest.h>

#include <algorithm>
#include <map>
#include <random>
#include <set>

#include "engine/tet_mesh.h"
#include "engine/topology_delta.h"

namespace serosa {
namespace {

TetMesh random_mesh(std::mt19937& rng, int nodes, int tets) {
  TetMesh m;
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  for (int i = 0; i < nodes; ++i) m.add_node(Vec3(u(rng), u(rng), u(rng)));
  std::uniform_int_distribution<int> node(0, nodes - 1);
  for (int i = 0; i < tets; ++i)
    m.add_tet({node(rng), node(rng), node(rng), node(rng)}, static_cast<std::uint16_t>(i % 3 + 1));
  return m;
}

TEST(TopologyDelta, NewNodesInterpolateParents) {
  TetMesh m;
  m.add_node(Vec3(0, 0, 0));
  m.add_node(Vec3(1, 0, 0));
  m.x[1] = Vec3(2, 0, 0);
  m.v[1] = Vec3(0, 4, 0);
  TopologyDelta d;
  NodeParent p;
  p.count = 2;
  p.nodes = {0, 1, -1, -1};
  p.weights = {0.75, 0.25, 0.0, 0.0};
  d.added_nodes.push_back(p);
  apply(m, d);
  ASSERT_EQ(m.num_nodes(), 3);
  EXPECT_DOUBLE_EQ(m.rest[2].x(), 0.25);
  EXPECT_DOUBLE_EQ(m.x[2].x(), 0.5);
  EXPECT_DOUBLE_EQ(m.v[2].y(), 1.0);
  EXPECT_EQ(m.topology_version, 1u);
  EXPECT_EQ(d.version_before, 0u);
  EXPECT_EQ(d.version_after, 1u);
}

TEST(TopologyDelta, RejectsInconsistentDeltaWithoutTouchingMesh) {
  std::mt19937 rng(1);
  TetMesh m = random_mesh(rng, 10, 5);
  const TetMesh before = m;
  TopologyDelta unsorted;
  unsorted.removed_tets = {3, 1};
  EXPECT_THROW(apply(m, unsorted), std::invalid_argument);
  TopologyDelta out_of_range;
  out_of_range.added_tets = {{0, 1, 2, 99}};
  out_of_range.added_groups = {1};
  EXPECT_THROW(apply(m, out_of_range), std::invalid_argument);
  TopologyDelta bad_weights;
  NodeParent p;
  p.count = 2;
  p.nodes = {0, 1, -1, -1};
  p.weights = {0.5, 0.6, 0, 0};
  bad_weights.added_nodes.push_back(p);
  EXPECT_THROW(apply(m, bad_weights), std::invalid_argument);
  EXPECT_EQ(m.tets, before.tets);
  EXPECT_EQ(m.num_nodes(), before.num_nodes());
  EXPECT_EQ(m.topology_version, 0u);
}

// Property: relabelling per-tet data with slot_of_added and moved_tets reproduces the mesh, and
// the set of tets afterwards is exactly (old - removed) + added.
TEST(TopologyDelta, SlotRulesMatchBruteForceOnRandomDeltas) {
  std::mt19937 rng(7);
  for (int trial = 0; trial < 3000; ++trial) {
    const int m0 = 1 + trial % 40;
    TetMesh m = random_mesh(rng, 12, m0);
    // Per-tet payload a consumer would carry (here: a unique label per tet).
    std::vector<int> label(m0);
    for (int i = 0; i < m0; ++i) label[i] = i;

    TopologyDelta d;
    std::set<int> removed;
    std::uniform_int_distribution<int> pick(0, m0 - 1);
    const int nrem = std::uniform_int_distribution<int>(0, m0)(rng);
    for (int i = 0; i < nrem; ++i) removed.insert(pick(rng));
    d.removed_tets.assign(removed.begin(), removed.end());
    const int nadd = std::uniform_int_distribution<int>(0, 2 * m0)(rng);
    std::uniform_int_distribution<int> node(0, 11);
    for (int i = 0; i < nadd; ++i) {
      d.added_tets.push_back({node(rng), node(rng), node(rng), node(rng)});
      d.added_groups.push_back(9);
    }
    std::multiset<Tet> expected;
    for (int i = 0; i < m0; ++i)
      if (!removed.count(i)) expected.insert(m.tets[i]);
    for (const Tet& t : d.added_tets) expected.insert(t);
    const std::vector<Tet> old_tets = m.tets;

    apply(m, d);

    ASSERT_EQ(std::multiset<Tet>(m.tets.begin(), m.tets.end()), expected);
    ASSERT_EQ(m.tets.size(), m.group.size());
    // Consumer-side relabel: removed labels die, added get -1-k, moves replayed in order.
    std::vector<int> relabel(
        std::max<std::size_t>(m.tets.size(), label.size()) + d.added_tets.size(), -999);
    for (int i = 0; i < m0; ++i) relabel[i] = removed.count(i) ? -999 : label[i];
    for (std::size_t k = 0; k < d.added_tets.size(); ++k)
      relabel[d.slot_of_added[k]] = -1 - static_cast<int>(k);
    for (auto [from, to] : d.moved_tets) relabel[to] = relabel[from];
    relabel.resize(m.tets.size());
    for (std::size_t i = 0; i < m.tets.size(); ++i) {
      const int l = relabel[i];
      ASSERT_NE(l, -999) << "trial " << trial << " slot " << i;
      const Tet& want = l >= 0 ? old_tets[l] : d.added_tets[-1 - l];
      ASSERT_EQ(m.tets[i], want) << "trial " << trial << " slot " << i;
    }
  }
}

}  // namespace
}  // namespace serosa
