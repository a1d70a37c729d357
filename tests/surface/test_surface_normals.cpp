// Render vertices and normals (surface/surface_normals.h): cube corners split in three, a smooth
// sphere keeps one vertex per node, cut edges and group borders split.
#include <gtest/gtest.h>

#include <cmath>
#include <map>
#include <numbers>
#include <random>
#include <set>

#include "cutting/convex_polygon.h"
#include "cutting/cut_mesh.h"
#include "engine/topology_delta.h"
#include "surface/cut_faces.h"
#include "surface/extract_surface.h"
#include "surface/surface_normals.h"
#include "surface_fixtures.h"

namespace serosa::surface {
namespace {

using test_meshes::kuhn_box;

/// Invariants of any RenderVertices: shapes, corners name the face's nodes, unit normals.
void expect_consistent(const SurfaceMesh& s, const RenderVertices& r) {
  ASSERT_EQ(r.tris.size(), s.faces.size());
  ASSERT_EQ(r.node.size(), r.normal.size());
  for (std::size_t i = 0; i < s.faces.size(); ++i)
    for (int k = 0; k < 3; ++k) {
      const std::int32_t v = r.tris[i][static_cast<std::size_t>(k)];
      ASSERT_GE(v, 0);
      ASSERT_LT(static_cast<std::size_t>(v), r.node.size());
      ASSERT_EQ(r.node[static_cast<std::size_t>(v)], s.faces[i][static_cast<std::size_t>(k)]);
    }
  for (const Vec3& n : r.normal) ASSERT_NEAR(n.norm(), 1.0, 1e-12);
  // Every render vertex is used, and (node, vertex) pairs are ordered by node.
  std::vector<char> used(r.node.size(), 0);
  for (const Tri& t : r.tris)
    for (std::int32_t v : t) used[static_cast<std::size_t>(v)] = 1;
  for (char u : used) ASSERT_TRUE(u);
  ASSERT_TRUE(std::is_sorted(r.node.begin(), r.node.end()));
}

/// Render vertices per node.
std::map<std::int32_t, std::vector<Vec3>> by_node(const RenderVertices& r) {
  std::map<std::int32_t, std::vector<Vec3>> out;
  for (std::size_t v = 0; v < r.node.size(); ++v) out[r.node[v]].push_back(r.normal[v]);
  return out;
}

TEST(SurfaceNormals, CubeCornersGetThreeNormalsEdgesTwoSidesOne) {
  const int n = 3;
  const TetMesh m = kuhn_box(n, n, n, 1, 1.0);
  const SurfaceMesh s = extract_surface(m);
  RenderVertices r;
  compute_render_vertices(s, m.x, {}, r);
  expect_consistent(s, r);
  for (const auto& [node, normals] : by_node(r)) {
    const Vec3& p = m.x[static_cast<std::size_t>(node)];
    int sides = 0;                           // number of cube sides the node is on
    std::set<std::pair<int, int>> expected;  // (axis, sign)
    for (int a = 0; a < 3; ++a) {
      if (p[a] == 0.0) expected.emplace(a, -1);
      if (p[a] == n) expected.emplace(a, 1);
    }
    sides = static_cast<int>(expected.size());
    ASSERT_EQ(static_cast<int>(normals.size()), sides) << "node " << node;
    std::set<std::pair<int, int>> got;
    for (const Vec3& nn : normals) {
      int axis = 0;
      nn.cwiseAbs().maxCoeff(&axis);
      EXPECT_NEAR(std::abs(nn[axis]), 1.0, 1e-12);
      got.emplace(axis, nn[axis] > 0 ? 1 : -1);
    }
    EXPECT_EQ(got, expected) << "node " << node;
  }
  // 8 corners x 3 + 12 edges x (n - 1) x 2 + 6 sides x (n - 1)^2.
  EXPECT_EQ(r.node.size(), 8u * 3 + 12u * (n - 1) * 2 + 6u * (n - 1) * (n - 1));
}

TEST(SurfaceNormals, WideCreaseAngleSmoothsTheCube) {
  const TetMesh m = kuhn_box(2, 2, 2, 1, 1.0);
  const SurfaceMesh s = extract_surface(m);
  RenderVertices r;
  compute_render_vertices(s, m.x, {.crease_angle_rad = std::numbers::pi * 0.6}, r);  // 108 deg
  expect_consistent(s, r);
  for (const auto& [node, normals] : by_node(r)) {
    ASSERT_EQ(normals.size(), 1u) << "node " << node;
    // Points away from the centre, area-weighted over the node's fan.
    const Vec3 out = m.x[static_cast<std::size_t>(node)] - Vec3(1, 1, 1);
    EXPECT_GT(normals[0].dot(out.normalized()), 0.5);
  }
  EXPECT_EQ(r.node.size(), 26u);  // every surface node of a 3x3x3-node cube
}

TEST(SurfaceNormals, SmoothSphereHasOneNormalPerNode) {
  // A grid ball: the cube [-1, 1]^3 mapped onto the unit ball (p |p|_inf / |p|_2), current
  // positions only (rest stays the cube; normals use x).
  const int n = 8;
  TetMesh m = kuhn_box(n, n, n, 1, 2.0 / n);
  for (Vec3& p : m.x) {
    p -= Vec3(1, 1, 1);
    if (p.norm() > 0.0) p *= p.cwiseAbs().maxCoeff() / p.norm();
  }
  const SurfaceMesh s = extract_surface(m);
  RenderVertices r;
  compute_render_vertices(s, m.x, {}, r);
  expect_consistent(s, r);
  std::set<std::int32_t> surface_nodes;
  for (const Tri& f : s.faces) surface_nodes.insert(f.begin(), f.end());
  EXPECT_EQ(r.node.size(), surface_nodes.size());
  for (std::size_t v = 0; v < r.node.size(); ++v) {
    const Vec3& p = m.x[static_cast<std::size_t>(r.node[v])];
    EXPECT_NEAR(p.norm(), 1.0, 1e-12);
    EXPECT_GT(r.normal[v].dot(p), 0.99) << "node " << r.node[v];  // radial
  }
}

TEST(SurfaceNormals, CutEdgesAndGroupBordersSplit) {
  // Flat side z = 0 of a 4 x 4 x 1 grid; mark the faces with centroid x < 2 as cut.
  const TetMesh m = kuhn_box(4, 4, 1, 1, 1.0);
  SurfaceMesh s = extract_surface(m);
  for (std::int32_t i = 0; i < s.num_faces(); ++i) {
    Vec3 c = Vec3::Zero();
    for (std::int32_t v : s.faces[i]) c += m.x[static_cast<std::size_t>(v)] / 3.0;
    s.face_cut[i] = c.z() == 0.0 && c.x() < 2.0 ? 1 : 0;
  }
  RenderVertices r;
  compute_render_vertices(s, m.x, {}, r);
  expect_consistent(s, r);
  const auto normals = by_node(r);
  for (std::int32_t node = 0; node < m.num_nodes(); ++node) {
    const Vec3& p = m.x[static_cast<std::size_t>(node)];
    if (p.z() != 0.0 || p.x() != 2.0 || p.y() == 0.0 || p.y() == 4.0) continue;
    // Inside the bottom side, on the wound's border: two vertices with the same normal -z.
    ASSERT_EQ(normals.at(node).size(), 2u) << "node " << node;
    for (const Vec3& nn : normals.at(node)) EXPECT_NEAR(nn.z(), -1.0, 1e-12);
  }
  // Without splitting cut edges those nodes have one vertex.
  RenderVertices joined;
  compute_render_vertices(s, m.x, {.split_cut_edges = false}, joined);
  // Nodes (2, 1..3, 0) and, on the cube's edges, (2, 0, 0) and (2, 4, 0) (their bottom cluster).
  EXPECT_EQ(joined.node.size() + 5, r.node.size());

  // Two groups meeting at x = 2: the border nodes split on the sides they share.
  const TetMesh g = kuhn_box(4, 2, 2, 2, 1.0);
  const SurfaceMesh sg = extract_surface(g);
  RenderVertices rg, rj;
  compute_render_vertices(sg, g.x, {}, rg);
  compute_render_vertices(sg, g.x, {.split_groups = false}, rj);
  expect_consistent(sg, rg);
  // Border ring x = 2: 8 nodes; the 4 mid-edge ones on one side each, the 4 corners on two.
  EXPECT_EQ(rg.node.size(), rj.node.size() + 4 + 4 * 2);
}

TEST(SurfaceNormals, RealCutWoundEdgesSplit) {
  // A blade through the whole organ, slightly tilted: the wound's rim on the top side splits.
  TetMesh m = kuhn_box(6, 4, 4, 1);
  const OriginalSurface original(m, extract_surface(m));
  const double h = 0.01;
  const Vec3 c(3.3 * h, 2 * h, 2 * h);
  const double t = 0.2 * h;  // tilt in x over the blade's height
  const cutting::ConvexPolygon blade({c + Vec3(t, -4 * h, 4 * h), c + Vec3(t, 4 * h, 4 * h),
                                      c + Vec3(-t, 4 * h, -4 * h), c + Vec3(-t, -4 * h, -4 * h)});
  cutting::CutResult cut = cutting::cut_mesh(m, blade);
  apply(m, cut.delta);
  const SurfaceMesh s = extract_surface(m, original);
  RenderVertices r;
  compute_render_vertices(s, m.x, {}, r);
  expect_consistent(s, r);
  // Nodes of the rim: on a top face (original, normal +z) and on a wound face (cut). Each has a
  // vertex with normal +z and a different one for the wound.
  std::set<std::int32_t> on_top, on_wound;
  for (std::int32_t i = 0; i < s.num_faces(); ++i)
    for (std::int32_t v : s.faces[i]) (s.face_cut[i] ? on_wound : on_top).insert(v);
  int rim = 0;
  const auto normals = by_node(r);
  for (std::int32_t v : on_wound) {
    if (!on_top.contains(v) || m.x[static_cast<std::size_t>(v)].z() < 4 * h - 1e-12) continue;
    ++rim;
    ASSERT_GE(normals.at(v).size(), 2u) << "rim node " << v;
  }
  EXPECT_GT(rim, 4);
}

TEST(SurfaceNormals, ZeroAreaFacesAndBadInput) {
  // All nodes of a tet at one point: zero-area faces get a unit fallback normal.
  TetMesh m;
  for (int i = 0; i < 4; ++i) m.add_node(Vec3(1, 2, 3));
  m.add_tet({0, 1, 2, 3}, 1);
  const SurfaceMesh s = extract_surface(m);
  RenderVertices r;
  compute_render_vertices(s, m.x, {}, r);
  expect_consistent(s, r);
  SurfaceMesh bad = s;
  bad.face_cut.pop_back();
  EXPECT_THROW(compute_render_vertices(bad, m.x, {}, r), std::invalid_argument);
  EXPECT_THROW(compute_render_vertices(s, std::span<const Vec3>(m.x).first(2), {}, r),
               std::invalid_argument);
}

}  // namespace
}  // namespace serosa::surface
