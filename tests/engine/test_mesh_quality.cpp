// tet_quality (engine/mesh_quality.h): 1 for a regular tet, invariant under rigid motions and
// uniform scaling, 0 when flat, negative when inverted.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <random>

#include "engine/box_meshes.h"
#include "engine/mesh_quality.h"

namespace serosa {
namespace {

// A regular tet of edge length `edge` (m): alternate corners of a cube, positively oriented.
std::array<Vec3, 4> regular(double edge) {
  const double s = edge / std::sqrt(2.0);
  std::array<Vec3, 4> p{Vec3(0, 0, 0), Vec3(s, s, 0), Vec3(s, 0, s), Vec3(0, s, s)};
  if (signed_volume(p[0], p[1], p[2], p[3]) < 0.0) std::swap(p[2], p[3]);
  return p;
}

double q(const std::array<Vec3, 4>& p) { return tet_quality(p[0], p[1], p[2], p[3]); }

TEST(TetQuality, RegularTetIsOne) {
  for (const double edge : {1e-9, 1e-4, 0.01, 1.0, 3.7, 1e5, 1e12}) {
    EXPECT_NEAR(q(regular(edge)), 1.0, 1e-12) << "edge " << edge;
  }
}

TEST(TetQuality, InvariantUnderRigidMotionAndUniformScaling) {
  std::mt19937 rng(42);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  std::uniform_real_distribution<double> log_scale(-6.0, 6.0);
  for (int trial = 0; trial < 5000; ++trial) {
    std::array<Vec3, 4> p;
    for (auto& x : p) x = Vec3(u(rng), u(rng), u(rng));
    const double q0 = q(p);
    ASSERT_GE(q0, -1.0);
    ASSERT_LE(q0, 1.0);
    // Random rotation (uniform quaternion), translation and scaling.
    Quat rot(u(rng), u(rng), u(rng), u(rng));
    if (rot.norm() < 1e-3) continue;
    rot.normalize();
    const Vec3 shift(u(rng), u(rng), u(rng));
    const double scale = std::pow(10.0, log_scale(rng));
    std::array<Vec3, 4> moved;
    for (int k = 0; k < 4; ++k)
      moved[static_cast<std::size_t>(k)] = scale * (rot * p[static_cast<std::size_t>(k)] + shift);
    EXPECT_NEAR(q(moved), q0, 1e-9) << "trial " << trial;
    // A mirror image (reflection) or an odd node permutation flips the sign only.
    std::array<Vec3, 4> mirrored = moved;
    for (auto& x : mirrored) x.x() = -x.x();
    EXPECT_NEAR(q(mirrored), -q0, 1e-9);
    EXPECT_NEAR(tet_quality(p[1], p[0], p[2], p[3]), -q0, 1e-12);
    // An even permutation keeps it.
    EXPECT_NEAR(tet_quality(p[1], p[2], p[0], p[3]), q0, 1e-12);
  }
}

TEST(TetQuality, FlatteningDrivesItToZero) {
  // Regular base in z = 0, apex at height h over its centroid: q falls monotonically to 0.
  const std::array<Vec3, 3> base{Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(0.5, std::sqrt(3.0) / 2, 0)};
  const Vec3 c = (base[0] + base[1] + base[2]) / 3.0;
  double previous = 1.0;
  for (double h = std::sqrt(2.0 / 3.0); h > 1e-12; h *= 0.5) {
    const double qh = tet_quality(base[0], base[1], base[2], c + Vec3(0, 0, h));
    EXPECT_GT(qh, 0.0);
    EXPECT_LT(qh, previous + 1e-12);
    previous = qh;
  }
  EXPECT_LT(previous, 1e-7);
  EXPECT_EQ(tet_quality(base[0], base[1], base[2], c), 0.0);
  EXPECT_EQ(tet_quality(base[0], base[1], base[2], Vec3(3, 4, 0)), 0.0);
  // Below the base: inverted, negative.
  EXPECT_LT(tet_quality(base[0], base[1], base[2], c - Vec3(0, 0, 0.1)), 0.0);
  // Degenerate node sets.
  EXPECT_EQ(tet_quality(base[0], base[0], base[1], base[2]), 0.0);
  EXPECT_EQ(tet_quality(c, c, c, c), 0.0);
  // Needle: three nodes almost on a line.
  EXPECT_LT(tet_quality(Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(2, 1e-9, 0), Vec3(0.5, 0, 1e-9)), 1e-6);
}

TEST(TetQuality, NonFiniteCoordinatesGiveNaN) {
  const double nan = std::nan("");
  const double inf = std::numeric_limits<double>::infinity();
  EXPECT_TRUE(
      std::isnan(tet_quality(Vec3(nan, 0, 0), Vec3(1, 0, 0), Vec3(0, 1, 0), Vec3(0, 0, 1))));
  EXPECT_TRUE(
      std::isnan(tet_quality(Vec3(inf, 0, 0), Vec3(1, 0, 0), Vec3(0, 1, 0), Vec3(0, 0, 1))));
}

TEST(TetQuality, MeshQualitiesOfAKuhnCubeAreEqualAndBelowOne) {
  const TetMesh m = fixtures::cube_mesh(fixtures::kuhn_tets());
  const auto qs = tet_qualities(m);
  ASSERT_EQ(qs.size(), 6U);
  for (const double x : qs) {
    EXPECT_GT(x, 0.0);
    EXPECT_LT(x, 1.0);
    EXPECT_NEAR(x, qs[0], 1e-12);  // the 6 Kuhn tets are congruent
  }
}

}  // namespace
}  // namespace serosa
