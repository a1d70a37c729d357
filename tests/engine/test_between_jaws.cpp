// Tissue between the jaws (engine/tool_geometry.h between_jaws): over random tool poses and
// openings, a point is between the jaws exactly when it lies in the wedge they span about the
// hinge, within the jaw length and the slab about their plane.
#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "engine/tool_geometry.h"

namespace serosa {
namespace {

TEST(BetweenJaws, ExactlyTheWedgeTheJawsSpanWithinTheSlab) {
  std::mt19937 rng(11);
  std::normal_distribution<double> g(0.0, 1.0);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  int inside = 0, outside = 0;
  for (int i = 0; i < 5000; ++i) {
    ToolState s;
    s.tip_m = {g(rng) * 0.05, g(rng) * 0.05, g(rng) * 0.05};
    const Quat q = Quat(g(rng), g(rng), g(rng), g(rng)).normalized();
    s.quat_wxyz = {q.w(), q.x(), q.y(), q.z()};
    const double jaw = 0.2 + 1.2 * u(rng);
    const ToolFrame f = tool_frame(s);
    // A point at angle a off the shaft in the jaw plane, radius r, height h off the plane.
    const double a = (u(rng) * 2.0 - 1.0) * 1.2 * jaw / 2.0;
    const double r = u(rng) * 1.2 * kJawLength;
    const double h = (u(rng) * 2.0 - 1.0) * 0.004;
    const Vec3 p = f.hinge + r * (std::cos(a) * f.forward + std::sin(a) * f.side) + h * f.pin;
    const bool want =
        std::abs(a) <= jaw / 2.0 && r <= kJawLength && std::abs(h) <= 0.003 && r > 0.0;
    // Clear of the borders by a hair either way.
    if (std::abs(std::abs(a) - jaw / 2.0) < 1e-9 || std::abs(r - kJawLength) < 1e-12 ||
        std::abs(std::abs(h) - 0.003) < 1e-12)
      continue;
    ASSERT_EQ(between_jaws(f, jaw, p, 0.003), want) << i;
    (want ? inside : outside)++;
  }
  EXPECT_GT(inside, 1000);
  EXPECT_GT(outside, 1000);
  // Behind the hinge is never between the jaws.
  ToolState s;
  const ToolFrame f = tool_frame(s);
  EXPECT_FALSE(between_jaws(f, 3.0, f.hinge - 0.001 * f.forward, 0.003));
}

}  // namespace
}  // namespace serosa
