// The best-fit rigid motion (engine/geometry/rigid_fit.h): it recovers any rigid motion of any
// point set exactly, never reflects, is least squares under noise, and falls back to matching
// centroids where the rotation is not defined.
#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <random>

#include "engine/geometry/rigid_fit.h"

namespace serosa::geometry {
namespace {

Mat3 random_rotation(std::mt19937& rng) {
  std::normal_distribution<double> n(0.0, 1.0);
  Eigen::Quaterniond q(n(rng), n(rng), n(rng), n(rng));
  q.normalize();
  return q.toRotationMatrix();
}

double cost(const RigidMotion& m, const std::vector<Vec3>& from, const std::vector<Vec3>& to) {
  double c = 0.0;
  for (std::size_t i = 0; i < from.size(); ++i)
    c += (m.rotation * from[i] + m.translation - to[i]).squaredNorm();
  return c;
}

TEST(RigidFit, RecoversEveryRigidMotionOfRandomPointSets) {
  std::mt19937 rng(11);
  std::uniform_real_distribution<double> u(-0.02, 0.02);
  std::uniform_int_distribution<int> count(3, 40);
  for (int trial = 0; trial < 3000; ++trial) {
    std::vector<Vec3> from(static_cast<std::size_t>(count(rng)));
    for (Vec3& p : from) p = Vec3(u(rng), u(rng), u(rng));
    if (trial % 5 == 1)  // nearly planar sets: a clip's anchors in a thin fold
      for (Vec3& p : from) p.z() *= 1e-3;
    const Mat3 r = random_rotation(rng);
    const Vec3 t(u(rng), u(rng), u(rng));
    std::vector<Vec3> to;
    for (const Vec3& p : from) to.push_back(r * p + t);
    const RigidMotion m = fit_rigid_motion(from, to);
    ASSERT_LT((m.rotation - r).norm(), 1e-8) << "trial " << trial;
    ASSERT_LT((m.translation - t).norm(), 1e-10) << "trial " << trial;
    ASSERT_NEAR(m.rotation.determinant(), 1.0, 1e-12);
  }
}

TEST(RigidFit, UnderNoiseNoNearbyMotionFitsBetter) {
  std::mt19937 rng(12);
  std::uniform_real_distribution<double> u(-0.02, 0.02), noise(-1e-3, 1e-3), small(-1e-3, 1e-3);
  for (int trial = 0; trial < 500; ++trial) {
    std::vector<Vec3> from(12), to;
    for (Vec3& p : from) p = Vec3(u(rng), u(rng), u(rng));
    const Mat3 r = random_rotation(rng);
    for (const Vec3& p : from) to.push_back(r * p + Vec3(noise(rng), noise(rng), noise(rng)));
    const RigidMotion best = fit_rigid_motion(from, to);
    const double c = cost(best, from, to);
    for (int k = 0; k < 10; ++k) {  // nudged motions cost more
      RigidMotion other = best;
      other.rotation =
          Eigen::AngleAxisd(0.02, Vec3(small(rng), small(rng), small(rng)).normalized()) *
          best.rotation;
      other.translation += Vec3(small(rng), small(rng), small(rng));
      ASSERT_GE(cost(other, from, to), c - 1e-15) << "trial " << trial;
    }
  }
}

TEST(RigidFit, WithoutADefinedRotationTheCentroidsAreMatched) {
  const std::vector<Vec3> line{Vec3(0, 0, 0), Vec3(0.01, 0, 0), Vec3(0.02, 0, 0)};
  std::vector<Vec3> moved;
  for (const Vec3& p : line) moved.push_back(p + Vec3(0.001, 0.002, 0.003));
  const RigidMotion m = fit_rigid_motion(line, moved);
  EXPECT_EQ(m.rotation, Mat3::Identity());
  EXPECT_LT((m.translation - Vec3(0.001, 0.002, 0.003)).norm(), 1e-15);
  const RigidMotion two =
      fit_rigid_motion({Vec3(0, 0, 0), Vec3(1, 0, 0)}, {Vec3(0, 1, 0), Vec3(0, 2, 0)});
  EXPECT_EQ(two.rotation, Mat3::Identity());
  EXPECT_LT((two.translation - Vec3(-0.5, 1.5, 0)).norm(), 1e-15);
  const RigidMotion none = fit_rigid_motion({}, {});
  EXPECT_EQ(none.rotation, Mat3::Identity());
  EXPECT_EQ(none.translation, Vec3::Zero());
  const RigidMotion mismatched = fit_rigid_motion({Vec3(1, 2, 3)}, {});
  EXPECT_EQ(mismatched.translation, Vec3::Zero());
}

}  // namespace
}  // namespace serosa::geometry
