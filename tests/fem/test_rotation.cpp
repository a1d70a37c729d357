// fem/rotation.h: Müller et al. 2016 extraction against the Irving et al. 2004 SVD polar factor,
// on random, inverted and near-singular deformation gradients.
#include "fem/rotation.h"

#include <gtest/gtest.h>

#include <random>

#include "fem_fixtures.h"

namespace serosa::fem {
namespace {

// tr(R^T F): the quantity both methods maximize over SO(3).
double score(const Mat3& r, const Mat3& f) { return (r.transpose() * f).trace(); }

void expect_rotation(const Mat3& r) {
  EXPECT_NEAR(r.determinant(), 1.0, 1e-9);
  EXPECT_LE((r.transpose() * r - Mat3::Identity()).norm(), 1e-9);
}

TEST(Rotation, SvdPolarOfRotatedStretchIsTheRotation) {
  std::mt19937 rng(7);
  for (int k = 0; k < 200; ++k) {
    const Mat3 q = fixtures::random_rotation(rng);
    const Mat3 s = Vec3(1.5, 0.8, 0.3).asDiagonal();
    const Mat3 v = fixtures::random_rotation(rng);
    const Mat3 f = q * v * s * v.transpose();  // rotation times SPD stretch
    EXPECT_LE((polar_rotation_svd(f) - q).norm(), 1e-9);
  }
}

TEST(Rotation, MullerMatchesSvdOnRandomAndInvertedMatrices) {
  std::mt19937 rng(11);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  int inverted = 0, slow = 0;
  for (int k = 0; k < 2000; ++k) {
    Mat3 f;
    for (int i = 0; i < 9; ++i) f(i / 3, i % 3) = u(rng);
    if (f.determinant() < 0.0) ++inverted;
    const Mat3 r_svd = polar_rotation_svd(f);
    Quat q = Quat::Identity();
    const bool converged = extract_rotation(f, q, 200);
    if (converged) {  // Müller alone reaches the same maximum when it converges
      EXPECT_NEAR(score(q.toRotationMatrix(), f), score(r_svd, f), 1e-7 * (1.0 + f.norm()));
    } else {
      ++slow;
    }
    q = Quat::Identity();
    const Mat3 r = robust_rotation(f, q, 20);
    expect_rotation(r_svd);
    expect_rotation(r);
    // Same maximum of tr(R^T F) (the rotation itself is unique when singular values differ).
    EXPECT_NEAR(score(r, f), score(r_svd, f), 1e-7 * (1.0 + f.norm())) << "case " << k;
  }
  EXPECT_GT(inverted, 500);  // about half of random matrices are inverted
  EXPECT_LT(slow, 50);       // nearly flat matrices: Müller is slow there, the SVD takes over
}

TEST(Rotation, InvertedTetGivesRotationNotReflection) {
  // A tet squashed through its base: F = diag(1, 1, -0.5). The reflection-free answer is I
  // (the sign goes into the smallest singular value), not diag(1, 1, -1).
  const Mat3 f = Vec3(1.0, 1.0, -0.5).asDiagonal();
  EXPECT_LE((polar_rotation_svd(f) - Mat3::Identity()).norm(), 1e-12);
  Quat q = Quat::Identity();
  extract_rotation(f, q);
  EXPECT_LE((q.toRotationMatrix() - Mat3::Identity()).norm(), 1e-9);
  // Same inverted stretch, rotated: recovers the rotation.
  std::mt19937 rng(3);
  for (int k = 0; k < 100; ++k) {
    const Mat3 rot = fixtures::random_rotation(rng);
    Quat qk = Quat::Identity();
    extract_rotation(rot * f, qk, 100);
    EXPECT_LE((qk.toRotationMatrix() - rot).norm(), 1e-6) << k;
  }
}

TEST(Rotation, NearSingularAndZeroStayRotations) {
  std::mt19937 rng(5);
  for (int k = 0; k < 200; ++k) {
    const Mat3 rot = fixtures::random_rotation(rng);
    const Mat3 f = rot * Vec3(1.0, 1e-3, 1e-12).asDiagonal();  // flattened to a line
    Quat q = Quat::Identity();
    const Mat3 r = robust_rotation(f, q);
    expect_rotation(r);
    expect_rotation(polar_rotation_svd(f));
    EXPECT_NEAR(score(r, f), score(polar_rotation_svd(f), f), 1e-9);
    EXPECT_LE((r - rot).norm(), 1e-6);
  }
  Quat q = Quat::Identity();
  extract_rotation(Mat3::Zero(), q);
  EXPECT_LE((q.toRotationMatrix() - Mat3::Identity()).norm(), 1e-15);
}

TEST(Rotation, WarmStartConvergesLinearly) {
  std::mt19937 rng(9);
  const Mat3 rot = fixtures::random_rotation(rng);
  const Mat3 s = Vec3(1.1, 0.9, 1.0).asDiagonal();
  // From the converged rotation of the last step, a 0.01 rad change: each iteration shrinks the
  // error by about 1 - (s_j + s_k) / tr = 1/3, so 3 iterations leave ~0.01 / 27 and 20 converge.
  const Mat3 rot2 = Eigen::AngleAxisd(0.01, Vec3::UnitZ()).toRotationMatrix() * rot;
  Quat q(rot);
  EXPECT_FALSE(extract_rotation(rot2 * s, q, 3));
  EXPECT_LE((q.toRotationMatrix() - rot2).norm(), 0.01 / 10.0);
  q = Quat(rot);
  EXPECT_TRUE(extract_rotation(rot2 * s, q, kRotationMaxIterations));
  EXPECT_LE((q.toRotationMatrix() - rot2).norm(), 1e-8);
}

}  // namespace
}  // namespace serosa::fem

namespace serosa::fem {
namespace {

// The rotation as a solver step sees it: an upright tet gets robust_rotation() from the
// extrapolated start, bit for bit.
TEST(StepRotation, AnUprightTetIsExtractedFromTheExtrapolatedStart) {
  std::mt19937 rng(5);
  std::uniform_real_distribution<double> u(-0.2, 0.2);
  for (int k = 0; k < 2000; ++k) {
    const Mat3 r0 = fixtures::random_rotation(rng);
    Mat3 f = r0;
    for (int i = 0; i < 9; ++i) f(i / 3, i % 3) += u(rng);
    if (f.determinant() <= 0.0) continue;
    const Quat prev(fixtures::random_rotation(rng));
    const Quat last(r0);
    Quat q = last;
    const Mat3 r = step_rotation(f, q, prev, kStepRotationTolerance);
    Quat expect = (last * prev.conjugate()) * last;
    expect.normalize();
    const Mat3 r_expect =
        robust_rotation(f, expect, kRotationMaxIterations, kStepRotationTolerance);
    ASSERT_EQ(r, r_expect);
    ASSERT_EQ(q.coeffs(), expect.coeffs());
  }
}

// A crushed tet, inside out with its two smaller signed singular values nearly cancelling (its
// rotation ill-determined), held still over many steps after moving: each step's rotation starts
// from the last and only climbs tr(R^T F), so it settles instead of flipping between branches (the
// extrapolated start and the SVD's global answer flipped such tets back and forth by up to 70
// degrees a step in the default scene). Thousands of random crushed tets and histories.
TEST(StepRotation, AStillCrushedInvertedTetSettlesWithoutFlipping) {
  std::mt19937 rng(17);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  for (int trial = 0; trial < 3000; ++trial) {
    const Mat3 uu = fixtures::random_rotation(rng), vv = fixtures::random_rotation(rng);
    const double s1 = 1.0 + 3.0 * std::abs(u(rng)), s2 = 0.05 + 0.2 * std::abs(u(rng));
    const double s3 = s2 * (1.0 + 0.05 * u(rng));
    const Mat3 f = uu * Vec3(s1, s2, -s3).asDiagonal() * vv.transpose();
    // Its last two rotations: somewhere near the answer, turning.
    const Mat3 near = polar_rotation_svd(f) * Eigen::AngleAxisd(0.5 * u(rng), Vec3::UnitX());
    Quat q(near);
    Quat prev(Mat3(near * Eigen::AngleAxisd(0.3 * u(rng), Vec3(u(rng), u(rng), 1.0).normalized())));
    double last_score = -1e300;
    double last_turn = 0.0;
    for (int k = 0; k < 40; ++k) {
      const Quat before = q;
      const Mat3 r = step_rotation(f, q, prev, kStepRotationTolerance);
      prev = before;
      ASSERT_NEAR(r.determinant(), 1.0, 1e-9);
      const double sc = score(r, f);
      ASSERT_GE(sc, last_score - 1e-12 * s1) << "trial " << trial << " step " << k;
      last_score = sc;
      last_turn = 2.0 * std::acos(std::min(1.0, std::abs(q.dot(before))));
    }
    EXPECT_LT(last_turn, 1e-3) << "trial " << trial;  // settled, not flipping
  }
}

}  // namespace
}  // namespace serosa::fem
