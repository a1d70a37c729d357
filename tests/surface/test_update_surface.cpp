// update_surface (incremental, from TopologyDelta) against full extraction after every step of
// thousands of random topology changes applied with engine's apply().
#include <gtest/gtest.h>

#include <algorithm>
#include <random>
#include <set>
#include <stdexcept>

#include "engine/topology_delta.h"
#include "surface/extract_surface.h"
#include "surface/update_surface.h"
#include "surface/validate_surface.h"
#include "surface_fixtures.h"

namespace serosa::surface {
namespace {

using test_meshes::kuhn_box;
using testing::cut_records;

#if defined(__SANITIZE_ADDRESS__)
constexpr int kSteps = 300;  // per seed; ASan is ~5x slower
#else
constexpr int kSteps = 1000;
#endif
using testing::orient_positive;
using testing::records;

/// Distinct random tet ids, ascending.
std::vector<std::int32_t> pick_tets(std::mt19937& rng, const TetMesh& m, int k) {
  std::set<std::int32_t> ids;
  if (m.num_tets() == 0) return {};
  std::uniform_int_distribution<std::int32_t> tet(0, m.num_tets() - 1);
  while (static_cast<int>(ids.size()) < std::min(k, m.num_tets())) ids.insert(tet(rng));
  return {ids.begin(), ids.end()};
}

/// A random topology change of one of four kinds: split tets at their centroid (the surface keeps
/// its faces, their owners move), carve tets out (holes, new boundary), add random tets over
/// existing nodes (overlaps, faces shared three times), regroup tets.
TopologyDelta random_delta(std::mt19937& rng, const TetMesh& m, int ngroups) {
  TopologyDelta d;
  std::uniform_int_distribution<int> group(1, ngroups);
  const int kind = static_cast<int>(rng() % 4);
  const bool big = m.num_tets() > 500;
  d.removed_tets = pick_tets(rng, m, static_cast<int>(rng() % (big ? 8 : 4)) + (kind == 2 ? 0 : 1));
  if (kind == 0) {  // split each removed tet into 4 around a new node at its centroid
    for (std::int32_t r : d.removed_tets) {
      const Tet& t = m.tets[static_cast<std::size_t>(r)];
      NodeParent p;
      p.count = 4;
      p.nodes = t;
      p.weights = {0.25, 0.25, 0.25, 0.25};
      const auto c = m.num_nodes() + static_cast<std::int32_t>(d.added_nodes.size());
      d.added_nodes.push_back(p);
      for (int i = 0; i < 4; ++i) {
        Tet s = t;
        s[static_cast<std::size_t>(i)] = c;
        d.added_tets.push_back(s);
        d.added_groups.push_back(m.group[static_cast<std::size_t>(r)]);
      }
    }
  } else if (kind == 2 && !big) {  // random tets over existing nodes
    std::uniform_int_distribution<std::int32_t> node(0, m.num_nodes() - 1);
    const int n = 1 + static_cast<int>(rng() % 4);
    while (static_cast<int>(d.added_tets.size()) < n) {
      Tet t{node(rng), node(rng), node(rng), node(rng)};
      if (std::set<std::int32_t>(t.begin(), t.end()).size() < 4) continue;
      if (signed_volume(m.rest[t[0]], m.rest[t[1]], m.rest[t[2]], m.rest[t[3]]) < 0)
        std::swap(t[2], t[3]);
      d.added_tets.push_back(t);
      d.added_groups.push_back(static_cast<std::uint16_t>(group(rng)));
    }
  } else if (kind == 3) {  // same tets, new groups
    for (std::int32_t r : d.removed_tets) {
      d.added_tets.push_back(m.tets[static_cast<std::size_t>(r)]);
      d.added_groups.push_back(static_cast<std::uint16_t>(group(rng)));
    }
  }  // kind 1 (and 2 on a big mesh): removal only
  return d;
}

void expect_same_as_full(const SurfaceMesh& s, const TetMesh& m, int step,
                         const OriginalSurface* original = nullptr) {
  const SurfaceMesh full = original ? extract_surface(m, *original) : extract_surface(m);
  ASSERT_EQ(records(s), records(full)) << "step " << step;
  ASSERT_EQ(cut_records(s), cut_records(full)) << "step " << step;
  ASSERT_EQ(s.groups.size(), full.groups.size()) << "step " << step;
  for (std::size_t g = 0; g < s.groups.size(); ++g) {
    ASSERT_EQ(s.groups[g].group, full.groups[g].group) << "step " << step;
    ASSERT_EQ(s.groups[g].count, full.groups[g].count) << "step " << step;
  }
  const auto errs = validate_surface(s, m);
  ASSERT_TRUE(errs.empty()) << "step " << step << ": " << errs.front();
}

/// Slots not listed in `changed` hold the same face as before (the contract SurfaceBvh relies on).
void expect_unlisted_slots_unchanged(const SurfaceMesh& before, const SurfaceMesh& after,
                                     const std::vector<std::int32_t>& changed, int step) {
  ASSERT_TRUE(std::is_sorted(changed.begin(), changed.end()));
  ASSERT_EQ(std::adjacent_find(changed.begin(), changed.end()), changed.end());
  std::vector<char> listed(static_cast<std::size_t>(after.num_faces()), 0);
  for (std::int32_t p : changed) {
    ASSERT_GE(p, 0);
    ASSERT_LT(p, after.num_faces());
    listed[static_cast<std::size_t>(p)] = 1;
  }
  for (std::int32_t i = 0; i < after.num_faces(); ++i) {
    if (listed[static_cast<std::size_t>(i)]) continue;
    ASSERT_LT(i, before.num_faces()) << "step " << step << ": new slot " << i << " not listed";
    ASSERT_EQ(after.faces[i], before.faces[i]) << "step " << step << " slot " << i;
    ASSERT_EQ(after.face_tet[i], before.face_tet[i]) << "step " << step << " slot " << i;
    ASSERT_EQ(after.face_group[i], before.face_group[i]) << "step " << step << " slot " << i;
    ASSERT_EQ(after.face_cut[i], before.face_cut[i]) << "step " << step << " slot " << i;
  }
}

TEST(UpdateSurface, EqualsFullExtractionAfterThousandsOfRandomDeltas) {
  for (unsigned seed : {1u, 2u, 3u}) {
    std::mt19937 rng(seed);
    const int ngroups = 2 + static_cast<int>(seed);
    TetMesh m = kuhn_box(4, 4, 3, ngroups);
    SurfaceMesh s = extract_surface(m);
    const OriginalSurface original(m, s);
    FaceTable table = build_face_table(m, s);
    std::vector<std::int32_t> changed;
    for (int step = 0; step < kSteps; ++step) {
      TopologyDelta d = random_delta(rng, m, ngroups);
      apply(m, d);
      const SurfaceMesh before = s;
      update_surface(s, table, m, d, &original, &changed);
      expect_unlisted_slots_unchanged(before, s, changed, step);
      expect_same_as_full(s, m, step, &original);
      if (step % 100 == 0) {
        ASSERT_EQ(table.tets, m.tets);
      }
      if (::testing::Test::HasFatalFailure()) return;
    }
  }
}

TEST(UpdateSurface, CarvingEverythingAwayLeavesNothing) {
  TetMesh m = kuhn_box(2, 2, 2, 2);
  SurfaceMesh s = extract_surface(m);
  FaceTable table = build_face_table(m, s);
  std::mt19937 rng(5);
  while (m.num_tets() > 0) {
    TopologyDelta d;
    d.removed_tets = pick_tets(rng, m, 3);
    apply(m, d);
    update_surface(s, table, m, d);
    expect_same_as_full(s, m, m.num_tets());
  }
  EXPECT_EQ(s.num_faces(), 0);
  EXPECT_TRUE(s.groups.empty());
  EXPECT_TRUE(table.faces.empty());
}

TEST(UpdateSurface, RejectsADeltaThatDoesNotFollowOn) {
  TetMesh m = kuhn_box(2, 2, 2);
  SurfaceMesh s = extract_surface(m);
  FaceTable table = build_face_table(m, s);
  TopologyDelta first;
  first.removed_tets = {0};
  apply(m, first);
  TopologyDelta second;
  second.removed_tets = {1};
  apply(m, second);
  EXPECT_THROW(update_surface(s, table, m, second), std::invalid_argument);  // skipped `first`
  EXPECT_THROW((void)build_face_table(m, s), std::invalid_argument);  // s is not m's boundary
}

// One set of nodes. The surface names mechanical nodes; after deforming and
// cutting, every surface vertex is read from the mechanical node it names, with no copy to drift.
TEST(UpdateSurface, SurfaceVerticesAreTheMechanicalNodes) {
  std::mt19937 rng(9);
  std::normal_distribution<double> noise(0.0, 1e-3);
  TetMesh m = kuhn_box(5, 4, 3, 2);
  SurfaceMesh s = extract_surface(m);
  FaceTable table = build_face_table(m, s);
  for (int step = 0; step < 50; ++step) {
    for (Vec3& x : m.x) x += Vec3(noise(rng), noise(rng), noise(rng));  // deform
    TopologyDelta d = random_delta(rng, m, 2);                          // cut or carve
    apply(m, d);
    update_surface(s, table, m, d);
    ASSERT_EQ(s.topology_version, m.topology_version);
    for (std::int32_t i = 0; i < s.num_faces(); ++i) {
      const Tet& t = m.tets[static_cast<std::size_t>(s.face_tet[i])];
      for (std::int32_t v : s.faces[i]) {
        ASSERT_GE(v, 0);
        ASSERT_LT(v, m.num_nodes());
        // The vertex is one of its tet's own nodes: the mechanical node, not a look-alike.
        ASSERT_NE(std::find(t.begin(), t.end(), v), t.end());
      }
    }
  }
  // Deforming without a topology change needs no surface update: a consumer reading the
  // surface's vertices through its ids sees the nodes' new positions.
  auto gather = [&] {
    std::vector<Vec3> p;
    for (const Tri& f : s.faces)
      for (std::int32_t v : f) p.push_back(m.x[static_cast<std::size_t>(v)]);
    return p;
  };
  const std::vector<Vec3> before = gather();
  for (Vec3& x : m.x) x = 2.0 * x + Vec3(0.0, 0.01, 0.0);
  const std::vector<Vec3> moved = gather();
  ASSERT_EQ(moved.size(), before.size());
  for (std::size_t i = 0; i < before.size(); ++i)
    EXPECT_EQ(moved[i], 2.0 * before[i] + Vec3(0.0, 0.01, 0.0));
  EXPECT_EQ(s.topology_version, m.topology_version);
}

}  // namespace
}  // namespace serosa::surface
