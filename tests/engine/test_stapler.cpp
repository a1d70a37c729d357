// The stapler's trigger and geometry (engine/stapler.h) over random jaw sequences and segments:
// it fires exactly once per closure from an armed opening, from the widest opening since the last
// fire; the knife lies in the closing plane between the staple lines; a segment meets the stapled
// region exactly when some point of it lies in the region grown by r (checked against dense
// sampling).
#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <cmath>
#include <random>

#include "engine/stapler.h"
#include "support/tool_pose.h"

namespace serosa {
namespace {

using test_support::pose;

TEST(StaplerTrigger, FiresOncePerClosureFromAnArmedOpeningWithTheWidestOpening) {
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> jaw(0.0, 0.6);
  std::bernoulli_distribution closed(0.15);
  for (int trial = 0; trial < 200; ++trial) {
    StaplerTrigger t;
    double widest = 0.0;  // the reference: widest since the last fire
    int fires = 0, expected = 0;
    for (int k = 0; k < 300; ++k) {
      const double a = closed(rng) ? 0.5 * kStaplerFireRad * jaw(rng) : jaw(rng);
      widest = std::max(widest, a);
      const std::optional<double> fired = t.update(a);
      const bool should = a <= kStaplerFireRad && widest >= kStaplerArmRad;
      ASSERT_EQ(fired.has_value(), should) << "trial " << trial << " step " << k;
      if (should) {
        ASSERT_EQ(*fired, widest);
        widest = a;
        ++expected;
      }
      fires += fired ? 1 : 0;
    }
    EXPECT_EQ(fires, expected);
  }
  // Held closed, it fires once; it needs the jaws opened past the arming angle again.
  StaplerTrigger t;
  EXPECT_FALSE(t.update(0.5).has_value());
  EXPECT_TRUE(t.update(0.0).has_value());
  EXPECT_FALSE(t.update(0.0).has_value());
  EXPECT_FALSE(t.update(0.5 * kStaplerArmRad).has_value());
  EXPECT_FALSE(t.update(0.0).has_value());
}

TEST(StaplerJaws, TheKnifeRunsInTheClosingPlaneBetweenTheStapleLines) {
  std::mt19937 rng(11);
  std::normal_distribution<double> n(0.0, 1.0);
  std::uniform_real_distribution<double> open(kStaplerArmRad, 0.6);
  for (int trial = 0; trial < 100; ++trial) {
    Eigen::Quaterniond q(n(rng), n(rng), n(rng), n(rng));
    q.normalize();
    const StaplerJaws j = stapler_jaws(pose(Vec3(n(rng), n(rng), n(rng)), q, 0.0), open(rng));
    ASSERT_LT((j.frame.transpose() * j.frame - Mat3::Identity()).norm(), 1e-12);
    // Its corners: on the jaws' edges (the wedge's sides) at the stapled length's two ends.
    const double t = std::tan(0.5 * j.opening_rad);
    for (const Vec3& p : knife_polygon(j)) {
      const Vec3 l = stapler_local(j, p);
      ASSERT_NEAR(l.y(), 0.0, 1e-12);
      ASSERT_EQ(staple_line_of(l), -1);
      const double end = l.z() < 0.5 * kCartridgeLength ? kStapleStart : kCartridgeLength;
      ASSERT_NEAR(l.z(), end, 1e-12);
      ASSERT_NEAR(std::abs(l.x()), end * t, 1e-12);
    }
    for (int k = 0; k < 2; ++k) {
      const Vec3 l = stapler_local(j, staple_line_hinge(j, k));
      ASSERT_NEAR(std::abs(l.y()), kStapleLineOffset, 1e-12);
      ASSERT_EQ(staple_line_of(l), k);
    }
  }
}

// Inside the stapled region grown by r, as the six half-spaces say it (the reference for the
// clipped segment).
bool in_grown_region(const StaplerJaws& j, const Vec3& p, double r) {
  const Vec3 l = stapler_local(j, p);
  const double t = std::tan(0.5 * j.opening_rad), slant = std::sqrt(1.0 + t * t);
  const double pin = kStapleLineOffset + kStapleLineHalfWidth + r;
  return l.z() >= kStapleStart - r && l.z() <= kCartridgeLength + r && std::abs(l.y()) <= pin &&
         std::abs(l.x()) - t * l.z() <= r * slant;
}

TEST(StaplerJaws, ASegmentMeetsTheStapledRegionWhereSomePointOfItLiesInside) {
  std::mt19937 rng(3);
  std::normal_distribution<double> n(0.0, 1.0);
  std::uniform_real_distribution<double> u(-0.01, 0.04), reach(0.0, 0.002);
  const StaplerJaws j =
      stapler_jaws(pose(Vec3(0, 0, 0.015), Eigen::Quaterniond::Identity(), 0.0), 0.5);
  int met = 0, missed = 0;
  for (int trial = 0; trial < 3000; ++trial) {
    const Vec3 a(0.3 * u(rng), 0.3 * u(rng), u(rng));
    const Vec3 b = a + 0.01 * Vec3(n(rng), n(rng), n(rng));
    const double r = reach(rng);
    bool sampled = false;
    constexpr int kSamples = 4000;
    for (int k = 0; k <= kSamples && !sampled; ++k)
      sampled = in_grown_region(j, a + (b - a) * (static_cast<double>(k) / kSamples), r);
    const bool meets = segment_meets_stapled_region(j, a, b, r);
    if (sampled) {
      ASSERT_TRUE(meets) << "trial " << trial;
    }
    if (meets && !sampled) {
      // Only a sliver between two samples can be missed by sampling: the clipped piece is short.
      bool near = false;
      for (int k = 0; k <= 40 * kSamples && !near; ++k)
        near = in_grown_region(j, a + (b - a) * (static_cast<double>(k) / (40 * kSamples)), r);
      ASSERT_TRUE(near) << "trial " << trial;
    }
    (meets ? met : missed)++;
  }
  EXPECT_GT(met, 300);
  EXPECT_GT(missed, 300);
}

}  // namespace
}  // namespace serosa
