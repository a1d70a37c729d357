// Scissors never cut through a clip (cutting/clip_guard.h): a polygon meets a clip exactly when
// some point of the clip's centre line lies within the clearance of the plane and over the
// polygon grown by it, checked against dense sampling over thousands of random clips and
// polygons, parallel and crossing ones included.
#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <random>

#include "cutting/clip_guard.h"

namespace serosa::cutting {
namespace {

Clip clip_at(const Vec3& hinge, const Mat3& frame) {
  Clip c;
  c.hinge_m = hinge;
  c.frame = frame;
  return c;
}

// max(|d| - r, -margin - r) minimised over dense samples of the centre line: <= 0 where it meets.
double sampled_gap(const ConvexPolygon& poly, const Clip& clip, double r) {
  double best = std::numeric_limits<double>::infinity();
  constexpr int kSamples = 4000;
  for (int i = 0; i <= kSamples; ++i) {
    const double t = static_cast<double>(i) / kSamples;
    const Vec3 p = clip.end(0) + t * (clip.end(1) - clip.end(0));
    best =
        std::min(best, std::max(std::abs(poly.signed_distance(p)) - r, -poly.inside_margin(p) - r));
  }
  return best;
}

TEST(ClipGuard, BladesAcrossAClipMeetItAndBladesBesideItDoNot) {
  // A clip along -y at x = 0 (its legs' width along x), scissors closing in the plane x = c.
  Mat3 frame;
  frame.col(0) = Vec3(0, 0, 1);
  frame.col(1) = Vec3(-1, 0, 0);
  frame.col(2) = Vec3(0, -1, 0);
  const Clip clip = clip_at(Vec3(0, 0.011, 0), frame);
  const auto blade_plane = [](double x) {
    return ConvexPolygon({Vec3(x, 0.012, 0), Vec3(x, -0.01, 0.008), Vec3(x, -0.01, -0.008)});
  };
  EXPECT_TRUE(polygon_meets_clip(blade_plane(0.0), clip));
  EXPECT_TRUE(polygon_meets_clip(blade_plane(kClipHalfWidth + 0.9 * kClipClearance), clip));
  EXPECT_FALSE(polygon_meets_clip(blade_plane(kClipHalfWidth + 1.1 * kClipClearance), clip));
  EXPECT_FALSE(polygon_meets_clip(blade_plane(0.02), clip));
  EXPECT_TRUE(polygon_meets_clips(blade_plane(0.0), {clip_at(Vec3(1, 1, 1), frame), clip}));
  EXPECT_FALSE(polygon_meets_clips(blade_plane(0.0), {}));
}

TEST(ClipGuard, MeetsExactlyWhereDenseSamplingSaysSo) {
  std::mt19937 rng(31);
  std::uniform_real_distribution<double> u(-0.012, 0.012);
  std::normal_distribution<double> n(0.0, 1.0);
  const double r = kClipHalfWidth + kClipClearance;
  int met = 0, missed = 0, checked = 0;
  for (int trial = 0; trial < 3000; ++trial) {
    Eigen::Quaterniond q(n(rng), n(rng), n(rng), n(rng));
    q.normalize();
    const Clip clip = clip_at(Vec3(u(rng), u(rng), u(rng)), q.toRotationMatrix());
    std::vector<Vec3> pts{Vec3(u(rng), u(rng), u(rng)), Vec3(u(rng), u(rng), u(rng)),
                          Vec3(u(rng), u(rng), u(rng))};
    if (trial % 4 == 0) {  // a plane parallel to the clip's line, near it
      const Vec3 along = clip.end(1) - clip.end(0);
      const Vec3 off = along.unitOrthogonal() * (u(rng) / 4.0);
      pts = {clip.end(0) + off - 0.3 * along, clip.end(1) + off + 0.2 * along,
             clip.end(0) + off + along.cross(off).normalized() * 0.01};
    }
    const std::optional<ConvexPolygon> poly = ConvexPolygon::make(pts);
    if (!poly || poly->area() < 1e-6) continue;
    const double gap = sampled_gap(*poly, clip, r);
    if (std::abs(gap) < 1e-5) continue;  // within sampling error of the boundary
    ++checked;
    const bool meets = polygon_meets_clip(*poly, clip);
    ASSERT_EQ(meets, gap < 0.0) << "trial " << trial << " gap " << gap;
    (meets ? met : missed) += 1;
  }
  EXPECT_GT(checked, 2500);
  EXPECT_GT(met, 300);
  EXPECT_GT(missed, 300);
}

}  // namespace
}  // namespace serosa::cutting
