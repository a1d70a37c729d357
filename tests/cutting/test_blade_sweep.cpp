// sweep_polygon: quads, hinge triangles, and every degenerate sweep counted, never thrown.
#include <gtest/gtest.h>

#include <cmath>

#include "cutting/blade_sweep.h"

namespace serosa::cutting {
namespace {

TEST(BladeSweep, TranslationGivesQuad) {
  SweepWarnings w;
  auto p = sweep_polygon({Vec3(0, 0, 0), Vec3(1, 0, 0)}, {Vec3(0, 1, 0), Vec3(1, 1, 0)}, w);
  ASSERT_TRUE(p);
  EXPECT_EQ(p->size(), 4u);
  EXPECT_NEAR(p->area(), 1.0, 1e-12);
  EXPECT_NEAR(std::abs(p->normal().z()), 1.0, 1e-12);
  EXPECT_EQ(w.skipped(), 0);
  EXPECT_EQ(w.non_planar, 0);
}

TEST(BladeSweep, HingeGivesTriangle) {
  SweepWarnings w;
  const double a = 0.3;
  auto p = sweep_polygon({Vec3(0, 0, 0), Vec3(2, 0, 0)},
                         {Vec3(0, 0, 0), Vec3(2 * std::cos(a), 2 * std::sin(a), 0)}, w);
  ASSERT_TRUE(p);
  EXPECT_EQ(p->size(), 3u);
  EXPECT_NEAR(p->area(), 0.5 * 4.0 * std::sin(a), 1e-12);
  EXPECT_EQ(w.skipped(), 0);
}

TEST(BladeSweep, DegenerateSweepsAreCounted) {
  SweepWarnings w;
  const BladeEdge e{Vec3(0, 0, 0), Vec3(1, 0, 0)};
  EXPECT_FALSE(sweep_polygon(e, e, w));  // no motion
  EXPECT_EQ(w.zero_area, 1);
  EXPECT_FALSE(sweep_polygon(e, {Vec3(0.5, 0, 0), Vec3(1.5, 0, 0)}, w));  // along the edge
  EXPECT_EQ(w.zero_area, 2);
  EXPECT_FALSE(sweep_polygon({Vec3(0, 0, 0), Vec3(0, 0, 0)}, e, w));  // zero length
  EXPECT_EQ(w.zero_length, 1);
  EXPECT_FALSE(sweep_polygon(e, {Vec3(0, std::nan(""), 0), Vec3(1, 0, 0)}, w));
  EXPECT_EQ(w.non_finite, 1);
  EXPECT_EQ(w.skipped(), 4);
}

TEST(BladeSweep, TwistedAndCrossedSweepsAreRepaired) {
  SweepWarnings w;
  // The second pose is lifted at its tip: a twisted quad, projected onto its best-fit plane.
  auto p = sweep_polygon({Vec3(0, 0, 0), Vec3(1, 0, 0)}, {Vec3(0, 1, 0), Vec3(1, 1, 0.2)}, w);
  ASSERT_TRUE(p);
  EXPECT_EQ(w.non_planar, 1);
  // Ends swapped (blade turned around): the crossed quad becomes its convex hull.
  auto q = sweep_polygon({Vec3(0, 0, 0), Vec3(1, 0, 0)}, {Vec3(1, 1, 0), Vec3(0, 1, 0)}, w);
  ASSERT_TRUE(q);
  EXPECT_NEAR(q->area(), 1.0, 1e-12);
}

}  // namespace
}  // namespace serosa::cutting
