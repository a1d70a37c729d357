// The invariant checker (cutting/validate.h) itself: it passes a correct cut and names each kind
// of broken result, so the property tests that rely on it can fail.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include "cut_helpers.h"
#include "mesh_fixtures.h"

namespace serosa::cutting {
namespace {

bool mentions(const CutCheckReport& r, const std::string& what) {
  for (const std::string& p : r.problems)
    if (p.find(what) != std::string::npos) return true;
  return false;
}

CutCheckOptions separated(double tol) {
  CutCheckOptions o;
  o.expect_separated = true;
  o.plane_tol_m = tol;
  o.geometry_tol_m = 4.0 * tol + 1e-12;
  return o;
}

TEST(CheckCut, PassesACorrectFullCutWithExactClippedVolume) {
  const TetMesh m = test_meshes::kuhn_cube(3, 1.0, 0.1, 4);
  const ConvexPolygon blade = testing::square(Vec3(0.2, 1.0, 0.3), Vec3(1.4, 1.6, 1.5), 50.0);
  const testing::Applied a = testing::cut_and_check(m, blade, true);
  ASSERT_TRUE(a.report.ok) << testing::problems(a.report);
  EXPECT_EQ(a.report.components, 2);
  EXPECT_GT(a.report.clipped_volume_m3, 1.0);
  EXPECT_NEAR(a.report.positive_volume_m3, a.report.clipped_volume_m3,
              1e-12 * a.report.volume_before_m3);
}

TEST(CheckCut, ClippedVolumeOfAnAxisPlaneIsTheSlab) {
  const TetMesh m = test_meshes::kuhn_cube(4);
  for (double z : {0.5, 1.0, 2.7})
    EXPECT_NEAR(clipped_positive_volume(m, Vec3::UnitZ(), z), 16.0 * (4.0 - z), 1e-12);
}

TEST(CheckCut, NamesEveryBrokenInvariant) {
  const TetMesh m = test_meshes::kuhn_cube(2);
  const ConvexPolygon blade = testing::square(Vec3(0.1, 1.0, 0.2), Vec3(1.0, 1.1, 1.0), 50.0);
  const CutResult cut = cut_mesh(m, blade);
  const double tol = cut.stats.tolerance_m;
  TetMesh good = m;
  TopologyDelta d = cut.delta;
  apply(good, d);
  ASSERT_TRUE(check_cut(m, good, blade, separated(tol)).ok);

  // Uncut: a tet crosses the blade, a piece lies on both sides, the positive volume is wrong.
  const CutCheckReport uncut = check_cut(m, m, blade, separated(tol));
  EXPECT_TRUE(mentions(uncut, "crosses the blade")) << testing::problems(uncut);
  EXPECT_TRUE(mentions(uncut, "both sides")) << testing::problems(uncut);
  EXPECT_TRUE(mentions(uncut, "exact clipped volume")) << testing::problems(uncut);

  // A tet dropped: volume lost, a boundary face off the old surface and off the blade.
  TetMesh dropped = good;
  dropped.tets.erase(dropped.tets.begin() + dropped.num_tets() / 2);
  dropped.group.erase(dropped.group.begin() + dropped.num_tets() / 2);
  const CutCheckReport r1 = check_cut(m, dropped, blade);
  EXPECT_TRUE(mentions(r1, "total volume")) << testing::problems(r1);
  EXPECT_TRUE(mentions(r1, "neither on the old surface")) << testing::problems(r1);

  // A tet moved to another group: per-group volume.
  TetMesh regrouped = good;
  regrouped.group[0] = regrouped.group[0] == 1 ? 2 : 1;
  EXPECT_TRUE(mentions(check_cut(m, regrouped, blade), "group"));

  // A non-finite position, an inverted tet, a face shared by three tets.
  TetMesh nan = good;
  nan.x.back().x() = std::numeric_limits<double>::quiet_NaN();
  EXPECT_TRUE(mentions(check_cut(m, nan, blade), "non-finite"));
  TetMesh inverted = good;
  std::swap(inverted.tets[0][2], inverted.tets[0][3]);
  EXPECT_FALSE(check_cut(m, inverted, blade).ok);
  TetMesh overshared = good;
  overshared.tets.push_back(overshared.tets[0]);
  overshared.group.push_back(overshared.group[0]);
  EXPECT_FALSE(check_cut(m, overshared, blade).ok);
}

// Per-group volume is conserved relative to the group's own volume, not the mesh's: a one-tet
// group among 384 whose volume changes by ~1e-10 of itself (3e-13 of the mesh's) is named.
TEST(CheckCut, PerGroupVolumeIsRelativeToTheGroup) {
  TetMesh m = test_meshes::kuhn_cube(4);
  m.group[0] = 3;
  const Tet& t = m.tets[0];
  std::int32_t inner = -1;  // tet 0's node inside the cube: moving it keeps the total volume
  for (std::int32_t v : t)
    if ((m.rest[static_cast<std::size_t>(v)].array() > 0.5).all() &&
        (m.rest[static_cast<std::size_t>(v)].array() < 3.5).all())
      inner = v;
  ASSERT_GE(inner, 0);
  TetMesh moved = m;
  moved.rest[static_cast<std::size_t>(inner)] += Vec3(1e-10, 2e-10, -1e-10);
  const double dv = std::abs(moved.rest_volume(0) - m.rest_volume(0));
  ASSERT_GT(dv, 1e-11 * m.rest_volume(0));
  ASSERT_LT(dv, 1e-12 * 64.0);  // under the mesh-relative bound
  const ConvexPolygon far = testing::square(Vec3::UnitZ(), Vec3(10, 10, 10), 1.0);
  const CutCheckReport r = check_cut(m, moved, far);
  EXPECT_TRUE(mentions(r, "group 3 volume")) << testing::problems(r);
  EXPECT_FALSE(mentions(r, "total volume")) << testing::problems(r);
  EXPECT_TRUE(check_cut(m, m, far).ok);
}

}  // namespace
}  // namespace serosa::cutting
