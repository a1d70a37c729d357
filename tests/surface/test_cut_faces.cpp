// Cut faces (surface/cut_faces.h): the flag follows the rest geometry, full extraction and the
// incremental update agree, on synthetic subdivisions (edge splits, exactly what a cut does to a
// face) and on real cuts from cutting/.
#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <set>

#include "cutting/convex_polygon.h"
#include "cutting/cut_mesh.h"
#include "engine/topology_delta.h"
#include "surface/cut_faces.h"
#include "surface/extract_surface.h"
#include "surface/update_surface.h"
#include "surface/validate_surface.h"
#include "surface_fixtures.h"

namespace serosa::surface {
namespace {

using test_meshes::kuhn_box;
using testing::cut_records;
using testing::records;

constexpr double kH = 0.01;  // grid cell edge, m (kuhn_box default)

/// Splits edge (a, b) of a random tet at its midpoint: every tet holding the edge becomes two
/// (a replaced by the midpoint, then b), so every face holding the edge is split exactly in two,
/// in its own plane. This is what a cut's patterns do to the faces they cross.
TopologyDelta split_edge_delta(std::mt19937& rng, const TetMesh& m) {
  TopologyDelta d;
  const auto t = static_cast<std::size_t>(rng() % static_cast<unsigned>(m.num_tets()));
  const int i = static_cast<int>(rng() % 4);
  const int j = (i + 1 + static_cast<int>(rng() % 3)) % 4;
  const std::int32_t a = m.tets[t][static_cast<std::size_t>(i)];
  const std::int32_t b = m.tets[t][static_cast<std::size_t>(j)];
  NodeParent p;
  p.count = 2;
  p.nodes = {a, b, -1, -1};
  p.weights = {0.5, 0.5, 0.0, 0.0};
  d.added_nodes.push_back(p);
  const std::int32_t mid = m.num_nodes();
  for (std::int32_t k = 0; k < m.num_tets(); ++k) {
    const Tet& q = m.tets[static_cast<std::size_t>(k)];
    const auto ia = std::find(q.begin(), q.end(), a);
    const auto ib = std::find(q.begin(), q.end(), b);
    if (ia == q.end() || ib == q.end()) continue;
    d.removed_tets.push_back(k);
    Tet s1 = q, s2 = q;
    s1[static_cast<std::size_t>(ia - q.begin())] = mid;
    s2[static_cast<std::size_t>(ib - q.begin())] = mid;
    d.added_tets.push_back(s1);
    d.added_tets.push_back(s2);
    d.added_groups.push_back(m.group[static_cast<std::size_t>(k)]);
    d.added_groups.push_back(m.group[static_cast<std::size_t>(k)]);
  }
  return d;
}

/// Removes up to k random tets (carving exposes interior faces: wounds).
TopologyDelta carve_delta(std::mt19937& rng, const TetMesh& m, int k) {
  std::set<std::int32_t> ids;
  for (int i = 0; i < k && m.num_tets() > 0; ++i)
    ids.insert(static_cast<std::int32_t>(rng() % static_cast<unsigned>(m.num_tets())));
  TopologyDelta d;
  d.removed_tets.assign(ids.begin(), ids.end());
  return d;
}

/// True when the face lies on a side of the box [0, X] x [0, Y] x [0, Z] (rest coordinates).
bool on_box(const TetMesh& m, const Tri& f, const Vec3& box) {
  for (int axis = 0; axis < 3; ++axis)
    for (double side : {0.0, box[axis]}) {
      bool all = true;
      for (std::int32_t v : f)
        all = all && std::abs(m.rest[static_cast<std::size_t>(v)][axis] - side) < 1e-12;
      if (all) return true;
    }
  return false;
}

TEST(CutFaces, WithoutAReferenceEveryFaceIsOriginal) {
  const TetMesh m = kuhn_box(3, 2, 2, 2);
  const SurfaceMesh s = extract_surface(m);
  ASSERT_EQ(s.face_cut.size(), s.faces.size());
  for (std::uint8_t c : s.face_cut) EXPECT_EQ(c, 0);
  EXPECT_TRUE(validate_surface(s, m).empty());
}

TEST(CutFaces, TheOriginalSurfaceIsOriginal) {
  const TetMesh m = kuhn_box(4, 3, 2, 3);
  const OriginalSurface original(m, extract_surface(m));
  EXPECT_EQ(original.size(), extract_surface(m).faces.size());
  const SurfaceMesh s = extract_surface(m, original);
  for (std::uint8_t c : s.face_cut) EXPECT_EQ(c, 0);
}

TEST(CutFaces, ContainsIsGeometric) {
  // Unit cube: its side z = 0 is two triangles split along (0,0,0)-(1,1,0) (Kuhn split).
  const TetMesh m = kuhn_box(1, 1, 1, 1, 1.0);
  const OriginalSurface original(m, extract_surface(m));
  // Inside the triangle y < x, touching its edge y = 0; and its corner triangle itself.
  EXPECT_TRUE(original.contains(Vec3(0.1, 0, 0), Vec3(0.2, 0, 0), Vec3(0.2, 0.05, 0), 1));
  EXPECT_TRUE(original.contains(Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(1, 1, 0), 1));
  EXPECT_TRUE(original.contains(Vec3(0.5, 0.1, 0), Vec3(0.9, 0.1, 0), Vec3(0.9, 0.5, 0), 1));
  // Within tolerance (1e-6 of the unit edge) off the plane: still on it; 1e-4 off: not.
  EXPECT_TRUE(original.contains(Vec3(0.5, 0.1, 1e-8), Vec3(0.9, 0.1, 0), Vec3(0.9, 0.5, 0), 1));
  EXPECT_FALSE(original.contains(Vec3(0.5, 0.1, 1e-4), Vec3(0.9, 0.1, 0), Vec3(0.9, 0.5, 0), 1));
  // On the plane but across both triangles: a face a cut could not have made from one.
  EXPECT_FALSE(original.contains(Vec3(0.2, 0.1, 0), Vec3(0.9, 0.1, 0), Vec3(0.3, 0.8, 0), 1));
  // Wrong group; inside the cube; spanning two sides.
  EXPECT_FALSE(original.contains(Vec3(0.1, 0, 0), Vec3(0.2, 0, 0), Vec3(0.2, 0.05, 0), 2));
  EXPECT_FALSE(original.contains(Vec3(0.5, 0.5, 0.5), Vec3(0.6, 0.5, 0.5), Vec3(0.5, 0.6, 0.5), 1));
  EXPECT_FALSE(original.contains(Vec3(0.5, 0.1, 0), Vec3(0.9, 0.1, 0), Vec3(0.9, 0, 0.3), 1));
  // A face of the mesh: classify_face reads its rest positions.
  const SurfaceMesh s = extract_surface(m);
  EXPECT_EQ(classify_face(s.faces[0], s.face_group[0], m, original), 0);
  EXPECT_EQ(classify_face(s.faces[0], s.face_group[0], m, OriginalSurface{}), 0);
}

// Edge splits only subdivide the original surface: every face stays original. Carving then
// exposes interior faces, which are wounds. Checked against the box's sides, face by face, after
// each step, for the full extraction and the incremental update.
TEST(CutFaces, SubdivisionKeepsOriginalAndCarvingMakesWounds) {
  for (unsigned seed : {3u, 4u}) {
    std::mt19937 rng(seed);
    TetMesh m = kuhn_box(4, 3, 3, 2);
    const Vec3 box(4 * kH, 3 * kH, 3 * kH);
    SurfaceMesh s = extract_surface(m);
    const OriginalSurface original(m, s);
    FaceTable table = build_face_table(m, s);
    int cut_seen = 0;
    for (int step = 0; step < 300 && m.num_tets() > 0; ++step) {
      TopologyDelta d = step % 5 == 4 ? carve_delta(rng, m, 2) : split_edge_delta(rng, m);
      apply(m, d);
      update_surface(s, table, m, d, &original);
      const SurfaceMesh full = extract_surface(m, original);
      ASSERT_EQ(records(s), records(full)) << "step " << step;
      ASSERT_EQ(cut_records(s), cut_records(full)) << "step " << step;
      for (std::int32_t i = 0; i < s.num_faces(); ++i) {
        ASSERT_EQ(s.face_cut[i], on_box(m, s.faces[i], box) ? 0 : 1)
            << "seed " << seed << " step " << step << " face " << i;
        cut_seen += s.face_cut[i];
      }
      const auto errs = validate_surface(s, m);
      ASSERT_TRUE(errs.empty()) << errs.front();
    }
    EXPECT_GT(cut_seen, 0);
  }
}

/// A square blade of half-size r (m) through point c with unit normal n.
cutting::ConvexPolygon square_blade(const Vec3& c, const Vec3& n, double r) {
  const Vec3 u = n.unitOrthogonal();
  const Vec3 w = n.cross(u);
  return cutting::ConvexPolygon(
      {c - r * u - r * w, c + r * u - r * w, c + r * u + r * w, c - r * u + r * w});
}

// Real cuts from cutting/: blades crossing the whole organ. Every face is either on the box (0)
// or on one of the blades' planes (1); full and incremental agree after every cut.
TEST(CutFaces, RealCutsFlagTheBladePlanes) {
  std::mt19937 rng(21);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  TetMesh m = kuhn_box(6, 5, 4, 2);
  const Vec3 box(6 * kH, 5 * kH, 4 * kH);
  SurfaceMesh s = extract_surface(m);
  const OriginalSurface original(m, s);
  FaceTable table = build_face_table(m, s);
  std::vector<std::pair<Vec3, double>> planes;  // (unit normal, offset)
  int wounds = 0;
  for (int cut = 0; cut < 6; ++cut) {
    const Vec3 c =
        box.cwiseProduct(Vec3(0.5 + 0.3 * u(rng), 0.5 + 0.3 * u(rng), 0.5 + 0.3 * u(rng)));
    const Vec3 n = Vec3(u(rng), u(rng), u(rng)).normalized();
    const cutting::ConvexPolygon blade = square_blade(c, n, 0.2);  // far larger than the box
    cutting::CutResult r = cutting::cut_mesh(m, blade);
    apply(m, r.delta);
    planes.emplace_back(blade.normal(), blade.offset());
    update_surface(s, table, m, r.delta, &original);
    const SurfaceMesh full = extract_surface(m, original);
    ASSERT_EQ(records(s), records(full)) << "cut " << cut;
    ASSERT_EQ(cut_records(s), cut_records(full)) << "cut " << cut;
    wounds = 0;
    for (std::int32_t i = 0; i < s.num_faces(); ++i) {
      const Tri& f = s.faces[i];
      bool on_a_blade = false;
      for (const auto& [pn, off] : planes) {
        bool all = true;
        for (std::int32_t v : f)
          all = all && std::abs(pn.dot(m.rest[static_cast<std::size_t>(v)]) - off) < 1e-9;
        on_a_blade = on_a_blade || all;
      }
      if (s.face_cut[i] == 0) {
        ASSERT_TRUE(on_box(m, f, box))
            << "cut " << cut << ": original face " << i << " off the box";
      } else {
        ASSERT_TRUE(on_a_blade) << "cut " << cut << ": wound face " << i << " off every blade";
        ASSERT_FALSE(on_box(m, f, box)) << "cut " << cut << ": wound face " << i << " on the box";
        ++wounds;
      }
    }
  }
  EXPECT_GT(wounds, 0);
}

// Random partial cuts (blades ending inside the organ) and deformation before each cut: the
// incremental flags still equal the full extraction's.
TEST(CutFaces, RandomPartialCutsIncrementalEqualsFull) {
  std::mt19937 rng(5);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  TetMesh m = kuhn_box(5, 5, 4, 3);
  const Vec3 box(5 * kH, 5 * kH, 4 * kH);
  SurfaceMesh s = extract_surface(m);
  const OriginalSurface original(m, s);
  FaceTable table = build_face_table(m, s);
  std::int64_t split = 0;
  for (int cut = 0; cut < 25; ++cut) {
    for (Vec3& x : m.x) x += Vec3(u(rng), u(rng), u(rng)) * 1e-4;  // deform (cuts use x)
    const Vec3 c =
        box.cwiseProduct(Vec3(0.5 + 0.5 * u(rng), 0.5 + 0.5 * u(rng), 0.5 + 0.5 * u(rng)));
    const Vec3 n = Vec3(u(rng), u(rng), u(rng)).normalized();
    const auto blade = cutting::ConvexPolygon::make(
        {c, c + kH * 3 * n.unitOrthogonal(), c + kH * 3 * n.cross(n.unitOrthogonal())});
    ASSERT_TRUE(blade.has_value());
    cutting::CutResult r = cutting::cut_mesh(m, *blade);
    split += r.stats.tets_removed;
    apply(m, r.delta);
    update_surface(s, table, m, r.delta, &original);
    const SurfaceMesh full = extract_surface(m, original);
    ASSERT_EQ(records(s), records(full)) << "cut " << cut;
    ASSERT_EQ(cut_records(s), cut_records(full)) << "cut " << cut;
    const auto errs = validate_surface(s, m);
    ASSERT_TRUE(errs.empty()) << errs.front();
  }
  EXPECT_GT(split, 100);  // the blades did cut
}

}  // namespace
}  // namespace serosa::surface
