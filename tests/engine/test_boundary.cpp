// face_census (engine/boundary.h) and the outward face table (engine/tet_faces.h): orientation
// derived geometrically on random tets, closed boxes, brute-force counts on random tet soups.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <map>
#include <random>
#include <set>
#include <tuple>

#include "engine/boundary.h"
#include "engine/box_meshes.h"
#include "engine/tet_faces.h"

namespace serosa {
namespace {

Vec3 at(const TetMesh& m, std::int32_t id) { return m.rest[static_cast<std::size_t>(id)]; }

// Right-hand (unnormalized, |n| = 2 * area) normal of a face.
Vec3 normal(const TetMesh& m, const Tri& f) {
  return (at(m, f[1]) - at(m, f[0])).cross(at(m, f[2]) - at(m, f[0]));
}

Vec3 centroid(const TetMesh& m, const Tri& f) {
  return (at(m, f[0]) + at(m, f[1]) + at(m, f[2])) / 3.0;
}

// Sum over faces of the signed volume of the tet (origin, face): the volume the surface encloses
// when every face winds outward.
double enclosed_volume(const TetMesh& m, const std::vector<BoundaryFace>& faces) {
  double v = 0.0;
  for (const auto& f : faces)
    v += signed_volume(Vec3::Zero(), at(m, f.nodes[0]), at(m, f.nodes[1]), at(m, f.nodes[2]));
  return v;
}

double area(const TetMesh& m, const std::vector<BoundaryFace>& faces) {
  double a = 0.0;
  for (const auto& f : faces) a += 0.5 * normal(m, f.nodes).norm();
  return a;
}

Tri sorted(Tri t) {
  std::sort(t.begin(), t.end());
  return t;
}

TEST(TetFaces, OutwardNormalPointsAwayFromOppositeNodeOnRandomTets) {
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  int checked = 0;
  while (checked < 5000) {
    TetMesh m;
    for (int k = 0; k < 4; ++k) m.add_node(Vec3(u(rng), u(rng), u(rng)));
    const double vol = signed_volume(m.rest[0], m.rest[1], m.rest[2], m.rest[3]);
    if (std::abs(vol) < 1e-6) continue;
    Tet t{0, 1, 2, 3};
    if (vol < 0.0) std::swap(t[2], t[3]);
    for (int k = 0; k < 4; ++k) {
      const Tri f = tet_face(t, k);
      const Vec3 opposite = at(m, t[static_cast<std::size_t>(k)]);
      // Face k is opposite local node k and does not contain it.
      EXPECT_EQ(std::count(f.begin(), f.end(), t[static_cast<std::size_t>(k)]), 0);
      EXPECT_GT(normal(m, f).dot(centroid(m, f) - opposite), 0.0);
    }
    ++checked;
  }
}

TEST(TetFaces, ParityMatchesWindingAgainstSortedKey) {
  // Two windings of the same face with opposite orientation must get opposite parities.
  const std::vector<Tet> tets{{0, 1, 2, 3}, {1, 0, 2, 4}};  // share face {0,1,2}, opposite sides
  const auto faces = sorted_tet_faces(tets);
  ASSERT_EQ(faces.size(), 8U);
  std::map<Tri, std::vector<std::uint8_t>> parity;
  for (const auto& f : faces) parity[f.key].push_back(f.parity);
  const auto& shared = parity[Tri{0, 1, 2}];
  ASSERT_EQ(shared.size(), 2U);
  EXPECT_NE(shared[0], shared[1]);
  EXPECT_TRUE(std::is_sorted(faces.begin(), faces.end(),
                             [](const TetFace& a, const TetFace& b) { return a.key < b.key; }));
}

TEST(FaceCensus, SingleTetIsFourOutwardFaces) {
  TetMesh m;
  m.add_node(Vec3(0, 0, 0));
  m.add_node(Vec3(1, 0, 0));
  m.add_node(Vec3(0, 1, 0));
  m.add_node(Vec3(0, 0, 1));
  m.add_tet({0, 1, 2, 3}, 5);
  const FaceCensus c = face_census(m);
  ASSERT_EQ(c.boundary.size(), 4U);
  EXPECT_EQ(c.interior, 0);
  EXPECT_EQ(c.overshared, 0);
  for (const auto& f : c.boundary) {
    EXPECT_EQ(f.tet, 0);
    EXPECT_EQ(f.group, 5);
    EXPECT_EQ(f.nodes[0], *std::min_element(f.nodes.begin(), f.nodes.end()));
  }
  EXPECT_NEAR(enclosed_volume(m, c.boundary), 1.0 / 6.0, 1e-15);
}

void expect_closed_outward_box(const TetMesh& m, const FaceCensus& c, const Vec3& lo,
                               const Vec3& hi, std::size_t faces) {
  ASSERT_EQ(c.boundary.size(), faces);
  EXPECT_EQ(c.overshared, 0);
  // Every face counted: 4m = boundary + 2 * interior.
  EXPECT_EQ(4 * static_cast<std::int64_t>(m.tets.size()),
            static_cast<std::int64_t>(c.boundary.size()) + 2 * c.interior);
  Vec3 mesh_centroid = Vec3::Zero();
  for (const auto& p : m.rest) mesh_centroid += p;
  mesh_centroid /= static_cast<double>(m.rest.size());
  for (const auto& f : c.boundary) {
    EXPECT_GT(normal(m, f.nodes).dot(centroid(m, f.nodes) - mesh_centroid), 0.0);
    // The face belongs to its tet, wound as one of the tet's outward faces.
    const Tet& t = m.tets[static_cast<std::size_t>(f.tet)];
    bool found = false;
    for (int k = 0; k < 4; ++k) {
      Tri g = tet_face(t, k);
      for (int r = 0; r < 3 && !found; ++r) {
        found = g == f.nodes;
        std::rotate(g.begin(), g.begin() + 1, g.end());
      }
    }
    EXPECT_TRUE(found);
  }
  const Vec3 d = hi - lo;
  EXPECT_NEAR(area(m, c.boundary), 2.0 * (d.x() * d.y() + d.y() * d.z() + d.z() * d.x()),
              1e-12 * d.squaredNorm());
  EXPECT_NEAR(enclosed_volume(m, c.boundary), d.prod(), 1e-12 * std::pow(d.norm(), 3));
}

TEST(FaceCensus, CubeInFiveOrSixTetsHasTwelveOutwardTriangles) {
  const Vec3 lo(-0.01, 0.02, 0.5), hi(0.03, 0.05, 0.51);
  for (const auto& split : {fixtures::five_tets(), fixtures::kuhn_tets()}) {
    const TetMesh m = fixtures::cube_mesh(split, lo, hi);
    const FaceCensus c = face_census(m);
    expect_closed_outward_box(m, c, lo, hi, 12);
    EXPECT_EQ(c.interior, split.size() == 5 ? 4 : 6);
  }
}

TEST(FaceCensus, RandomGridsAreClosedConformingBoxes) {
  std::mt19937 rng(11);
  for (int trial = 0; trial < 40; ++trial) {
    const int k = 1 + trial % 5;
    const double size = 0.01 + 0.1 * trial;
    const auto xs = test_meshes::random_spacing(rng, k, size);
    const auto ys = test_meshes::random_spacing(rng, k, 2.0 * size);
    const auto zs = test_meshes::random_spacing(rng, k, 0.5 * size);
    const TetMesh m = test_meshes::kuhn_lattice(xs, ys, zs, 3);
    const FaceCensus c = face_census(m);
    expect_closed_outward_box(m, c, Vec3::Zero(), Vec3(size, 2.0 * size, 0.5 * size),
                              static_cast<std::size_t>(12 * k * k));
    // Sorted by (group, sorted key).
    EXPECT_TRUE(std::is_sorted(c.boundary.begin(), c.boundary.end(),
                               [](const BoundaryFace& a, const BoundaryFace& b) {
                                 return std::make_tuple(a.group, sorted(a.nodes)) <
                                        std::make_tuple(b.group, sorted(b.nodes));
                               }));
    for (const auto& f : c.boundary) EXPECT_EQ(f.group, m.group[static_cast<std::size_t>(f.tet)]);
  }
}

TEST(FaceCensus, MatchesBruteForceOnRandomTetSoups) {
  // Random subsets of a grid's tets with random duplicates: compare with a std::map count.
  std::mt19937 rng(3);
  const TetMesh grid = test_meshes::kuhn_lattice({0, 1, 2, 3}, {0, 1, 2}, {0, 1, 2});
  for (int trial = 0; trial < 300; ++trial) {
    TetMesh m;
    m.rest = grid.rest;
    m.fill_node_state();
    std::uniform_int_distribution<std::size_t> pick(0, grid.tets.size() - 1);
    const int count = 1 + static_cast<int>(rng() % 60);
    for (int i = 0; i < count; ++i) {
      const std::size_t t = pick(rng);
      m.add_tet(grid.tets[t], static_cast<std::uint16_t>(rng() % 4));
    }
    std::map<Tri, std::vector<std::int32_t>> owners;
    for (std::int32_t i = 0; i < m.num_tets(); ++i)
      for (int k = 0; k < 4; ++k)
        owners[sorted(tet_face(m.tets[static_cast<std::size_t>(i)], k))].push_back(i);
    std::set<std::pair<Tri, std::int32_t>> expected_boundary;
    std::int64_t interior = 0, overshared = 0;
    for (const auto& [key, tets] : owners) {
      if (tets.size() == 1) expected_boundary.insert({key, tets[0]});
      if (tets.size() == 2) ++interior;
      if (tets.size() >= 3) ++overshared;
    }
    const FaceCensus c = face_census(m);
    std::set<std::pair<Tri, std::int32_t>> got;
    for (const auto& f : c.boundary) got.insert({sorted(f.nodes), f.tet});
    EXPECT_EQ(got, expected_boundary);
    EXPECT_EQ(got.size(), c.boundary.size());
    EXPECT_EQ(c.interior, interior);
    EXPECT_EQ(c.overshared, overshared);
  }
}

TEST(FaceCensus, EmptyMeshHasNoFaces) {
  const FaceCensus c = face_census(TetMesh{});
  EXPECT_TRUE(c.boundary.empty());
  EXPECT_EQ(c.interior, 0);
  EXPECT_EQ(c.overshared, 0);
}

}  // namespace
}  // namespace serosa
