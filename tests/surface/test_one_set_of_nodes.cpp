// One set of nodes: the surface, its render vertices and its collision BVH name
// TetMesh nodes and read their positions from TetMesh::x; after deformation and subdivision every
// surface vertex is the mechanical node it names.
#include <gtest/gtest.h>

#include <algorithm>
#include <random>

#include "cutting/convex_polygon.h"
#include "cutting/cut_mesh.h"
#include "engine/geometry/surface_bvh.h"
#include "engine/geometry/tet_extent.h"
#include "engine/topology_delta.h"
#include "surface/cut_faces.h"
#include "surface/extract_surface.h"
#include "surface/surface_normals.h"
#include "surface/update_surface.h"
#include "surface_fixtures.h"

namespace serosa::surface {
namespace {
using geometry::SurfaceBvh;

using test_meshes::kuhn_box;

#if defined(__SANITIZE_ADDRESS__)
constexpr int kCuts = 3;  // each real cut of the whole organ costs seconds under ASan
#else
constexpr int kCuts = 8;
#endif

/// Rotation by angle (rad) about the unit axis.
Mat3 rotation(double angle, const Vec3& axis) {
  return Eigen::AngleAxisd(angle, axis.normalized()).toRotationMatrix();
}

/// Checks every surface face against its owning tet, in current positions: the face's corners,
/// read through the surface's node ids, are exactly the current positions of the owning tet's
/// face nodes (the mechanical nodes), and the render vertices name the same nodes.
void expect_surface_is_mechanical(const SurfaceMesh& s, const TetMesh& m, const RenderVertices& r) {
  ASSERT_EQ(s.topology_version, m.topology_version);
  ASSERT_EQ(r.tris.size(), s.faces.size());
  for (std::int32_t i = 0; i < s.num_faces(); ++i) {
    const Tet& t = m.tets[static_cast<std::size_t>(s.face_tet[i])];
    // The tet's face that the surface face is: the one whose opposite node is not in it.
    int l = -1;
    for (int k = 0; k < 4; ++k)
      if (std::find(s.faces[i].begin(), s.faces[i].end(), t[static_cast<std::size_t>(k)]) ==
          s.faces[i].end())
        l = k;
    ASSERT_GE(l, 0) << "face " << i << " is not a face of its tet";
    Tri g{};
    outward_face(t, l, g[0], g[1], g[2]);
    // Same corners, same orientation (up to rotation), same current positions.
    const Tri f = testing::canonical_rotation(s.faces[i]);
    ASSERT_EQ(f, testing::canonical_rotation(g)) << "face " << i;
    for (int k = 0; k < 3; ++k) {
      const auto node = static_cast<std::size_t>(s.faces[i][static_cast<std::size_t>(k)]);
      const auto rv = static_cast<std::size_t>(
          r.tris[static_cast<std::size_t>(i)][static_cast<std::size_t>(k)]);
      ASSERT_EQ(static_cast<std::size_t>(r.node[rv]), node);
    }
  }
}

TEST(OneSetOfNodes, DeformedAndSubdividedSurfaceReadsTheMechanicalNodes) {
  std::mt19937 rng(77);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  TetMesh m = kuhn_box(6, 5, 4, 2);
  SurfaceMesh s = extract_surface(m);
  const OriginalSurface original(m, s);
  FaceTable table = build_face_table(m, s);
  const double h = 0.01;
  SurfaceBvh bvh;
  std::vector<std::int32_t> changed;
  for (int step = 0; step < kCuts; ++step) {
    // Deform: a rigid motion plus noise, applied to the mechanical nodes only.
    const Mat3 rot = rotation(0.1 * u(rng), Vec3(u(rng), u(rng), 1.0));
    for (Vec3& x : m.x) x = rot * x + Vec3(u(rng), u(rng), u(rng)) * 1e-4;
    // Subdivide: a real cut through the whole deformed mesh (new nodes interpolate x).
    Vec3 lo, hi;
    geometry::point_box(m.x, lo, hi);
    const Vec3 c = lo + (hi - lo).cwiseProduct(Vec3(0.5 + 0.3 * u(rng), 0.5 + 0.3 * u(rng), 0.5));
    const Vec3 n = Vec3(u(rng), u(rng), u(rng)).normalized();
    const Vec3 a = n.unitOrthogonal(), b = n.cross(a);
    const double half = 20 * h;  // wider than the organ: a complete cut
    const cutting::ConvexPolygon blade({c - half * a - half * b, c + half * a - half * b,
                                        c + half * a + half * b, c - half * a + half * b});
    cutting::CutResult cut = cutting::cut_mesh(m, blade);
    apply(m, cut.delta);
    update_surface(s, table, m, cut.delta, &original, &changed);
    RenderVertices r;
    compute_render_vertices(s, m.x, {}, r);
    expect_surface_is_mechanical(s, m, r);
    if (::testing::Test::HasFatalFailure()) return;
    // The collision BVH, updated locally, finds every surface node exactly where TetMesh::x
    // has it: distance 0 on a face that holds it.
    if (step == 0) {
      bvh.build(s, m.x);
    } else {
      bvh.update(s, changed, m.x);
    }
    for (const Tri& f : s.faces)
      for (std::int32_t v : f) {
        const auto hit = bvh.closest_point(m.x, m.x[static_cast<std::size_t>(v)]);
        ASSERT_TRUE(hit.has_value());
        ASSERT_EQ(hit->distance, 0.0) << "node " << v;
      }
    // Every node a cut added and the surface uses sits where its parents put it: x is the
    // weighted sum of the parents' x (no copy of an older position anywhere).
    const std::int32_t first_new =
        m.num_nodes() - static_cast<std::int32_t>(cut.delta.added_nodes.size());
    for (const Tri& f : s.faces)
      for (std::int32_t v : f) {
        if (v < first_new) continue;
        const NodeParent& p = cut.delta.added_nodes[static_cast<std::size_t>(v - first_new)];
        Vec3 x = Vec3::Zero();
        for (int k = 0; k < p.count; ++k)
          x += p.weights[static_cast<std::size_t>(k)] *
               m.x[static_cast<std::size_t>(p.nodes[static_cast<std::size_t>(k)])];
        ASSERT_LT((x - m.x[static_cast<std::size_t>(v)]).norm(), 1e-15) << "node " << v;
      }
  }
  // Deforming again without a topology change: normals computed through the ids follow the
  // nodes (a rotated mesh has rotated normals), with no surface update in between.
  RenderVertices before;
  compute_render_vertices(s, m.x, {}, before);
  const Mat3 rot = rotation(0.7, Vec3(1, 2, 3));
  for (Vec3& x : m.x) x = rot * x;
  RenderVertices after;
  compute_render_vertices(s, m.x, {}, after);
  ASSERT_EQ(after.node, before.node);
  for (std::size_t v = 0; v < after.normal.size(); ++v)
    EXPECT_LT((after.normal[v] - rot * before.normal[v]).norm(), 1e-9);
}

}  // namespace
}  // namespace serosa::surface
