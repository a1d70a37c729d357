// ConvexPolygon: validation messages, plane, inclusion and segment intersection.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <random>

#include "cutting/convex_polygon.h"

namespace serosa::cutting {
namespace {

ConvexPolygon unit_square() {
  return ConvexPolygon({Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(1, 1, 0), Vec3(0, 1, 0)});
}

void expect_rejected(std::vector<Vec3> pts, const std::string& fragment) {
  try {
    ConvexPolygon p(std::move(pts));
    FAIL() << "accepted a bad polygon, expected: " << fragment;
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find(fragment), std::string::npos) << e.what();
  }
}

TEST(ConvexPolygon, PlaneAndArea) {
  const ConvexPolygon p = unit_square();
  EXPECT_NEAR(p.normal().z(), 1.0, 1e-15);
  EXPECT_NEAR(p.offset(), 0.0, 1e-15);
  EXPECT_NEAR(p.area(), 1.0, 1e-15);
  EXPECT_NEAR(p.diameter(), std::sqrt(2.0), 1e-15);
  EXPECT_NEAR(p.signed_distance(Vec3(0.3, 0.2, 0.5)), 0.5, 1e-15);
  // Reversed order flips the normal.
  const ConvexPolygon q({Vec3(0, 1, 2), Vec3(1, 1, 2), Vec3(1, 0, 2), Vec3(0, 0, 2)});
  EXPECT_NEAR(q.normal().z(), -1.0, 1e-15);
  EXPECT_NEAR(q.offset(), -2.0, 1e-15);
}

TEST(ConvexPolygon, RejectsBadInput) {
  expect_rejected({Vec3(0, 0, 0), Vec3(1, 0, 0)}, "at least 3");
  expect_rejected({Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(0, std::nan(""), 0)}, "non-finite");
  expect_rejected(
      {Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(0, std::numeric_limits<double>::infinity(), 0)},
      "non-finite");
  expect_rejected({Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(2, 0, 0)}, "zero area");
  expect_rejected({Vec3(0, 0, 0), Vec3(0, 0, 0), Vec3(0, 0, 0)}, "zero size");
  expect_rejected({Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(1, 0, 0), Vec3(0, 1, 0)}, "zero length");
  expect_rejected({Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(1, 1, 0.1), Vec3(0, 1, 0)}, "off the plane");
  expect_rejected({Vec3(0, 0, 0), Vec3(2, 0, 0), Vec3(1, 0.2, 0), Vec3(2, 2, 0), Vec3(0, 2, 0)},
                  "not convex");
  // A pentagram turns the same way at every point but winds twice.
  std::vector<Vec3> star;
  for (int i = 0; i < 5; ++i) {
    const double a = 2.0 * M_PI * (2 * i) / 5.0;
    star.emplace_back(std::cos(a), std::sin(a), 0.0);
  }
  expect_rejected(star, "winds");
  std::string why;
  EXPECT_FALSE(ConvexPolygon::make({Vec3(0, 0, 0)}, 1e-6, &why));
  EXPECT_NE(why.find("at least 3"), std::string::npos);
}

TEST(ConvexPolygon, InclusionMatchesBruteForce) {
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> u(-0.5, 1.5);
  const ConvexPolygon p = unit_square();
  for (int i = 0; i < 2000; ++i) {
    const Vec3 q(u(rng), u(rng), u(rng));
    const bool inside = q.x() >= 0 && q.x() <= 1 && q.y() >= 0 && q.y() <= 1;
    EXPECT_EQ(p.contains_projection(q), inside) << q.transpose();
    const double margin = std::min({q.x(), 1 - q.x(), q.y(), 1 - q.y()});
    EXPECT_NEAR(p.inside_margin(q), margin, 1e-12);
  }
}

TEST(ConvexPolygon, SegmentIntersection) {
  const ConvexPolygon p = unit_square();
  auto hit = p.intersect_segment(Vec3(0.5, 0.5, -1), Vec3(0.5, 0.5, 3));
  ASSERT_TRUE(hit);
  EXPECT_EQ(hit->kind, SegmentHit::Kind::kTransverse);
  EXPECT_NEAR(hit->t0, 0.25, 1e-15);
  EXPECT_FALSE(p.intersect_segment(Vec3(1.5, 0.5, -1), Vec3(1.5, 0.5, 1)));   // outside
  EXPECT_FALSE(p.intersect_segment(Vec3(0.5, 0.5, 0.1), Vec3(0.5, 0.5, 1)));  // one side
  auto end = p.intersect_segment(Vec3(0.5, 0.5, 0.0), Vec3(0.5, 0.5, 1));     // endpoint on it
  ASSERT_TRUE(end);
  EXPECT_EQ(end->t0, 0.0);
  auto cop = p.intersect_segment(Vec3(-1, 0.5, 0), Vec3(3, 0.5, 0));  // coplanar, clipped
  ASSERT_TRUE(cop);
  EXPECT_EQ(cop->kind, SegmentHit::Kind::kCoplanar);
  EXPECT_NEAR(cop->t0, 0.25, 1e-15);
  EXPECT_NEAR(cop->t1, 0.5, 1e-15);
  EXPECT_FALSE(p.intersect_segment(Vec3(-1, 2, 0), Vec3(3, 2, 0)));  // coplanar, outside
}

}  // namespace
}  // namespace serosa::cutting
