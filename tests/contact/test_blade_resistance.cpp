// The torque of tissue between closing scissor blades (contact/blade_resistance.h): against the
// closed form for blades inside a block of tissue, and its invariants (zero unless closing on
// tissue, growing as they close, linear in the modulus, unchanged by a rigid motion of the
// whole scene).
#include <gtest/gtest.h>

#include <cmath>

#include "contact/blade_resistance.h"
#include "engine/tool_geometry.h"
#include "support/test_meshes.h"

namespace serosa::contact {
namespace {

// A 4 x 4 cm block of tissue, 1 cm thick (z), of 1 mm cubes.
TetMesh block() { return test_meshes::kuhn_box(40, 40, 10, 1, 0.001); }

LameTable table(double young_pa) {
  Material m;
  m.young_pa = young_pa;
  m.poisson = 0.45;
  LameTable t;
  t.fallback = lame(m);
  return t;
}

// Scissors inside the block: shaft along +x, blades opening in the x-y plane (side +y, pin +z),
// hinge at (5, 20, 5) mm.
ToolState scissors(double jaw_rad) {
  ToolState s;
  s.quat_wxyz = {0.5, 0.5, 0.5, 0.5};  // local (x, y, z) -> world (y, z, x)
  s.tip_m = {0.005 + kJawLength, 0.02, 0.005};
  s.jaw_rad = jaw_rad;
  return s;
}

TEST(BladeResistance, MatchesTheClosedFormForBladesInsideTissue) {
  const TetMesh mesh = block();
  BladeResistance b;
  b.update(mesh, table(3e4));
  const ToolFrame f = tool_frame(scissors(0.0));
  ASSERT_LT((f.hinge - Vec3(0.005, 0.02, 0.005)).norm(), 1e-12);
  ASSERT_LT((f.pin - Vec3(0, 0, 1)).norm(), 1e-12);
  // Closing from 1 rad to 0.4 rad: both sides of the wedge, each (1 - 0.4) / 2 rad wide, hold
  // tissue out to the blade length: torque = s * 2 * ((1 - 0.4) / 2) * L^3 / 3, s = k E.
  const double expected =
      kShearStrengthPerYoung * 3e4 * (1.0 - 0.4) * std::pow(kJawLength, 3) / 3.0;
  EXPECT_NEAR(b.load(mesh, scissors(0.4), 1.0).torque_nm, expected, 0.2 * expected);
  // Each blade presses with the wedge's strength times its area, s (1 - 0.4) L^2 / 2.
  const double force = kShearStrengthPerYoung * 3e4 * (1.0 - 0.4) * kJawLength * kJawLength / 2.0;
  EXPECT_NEAR(b.load(mesh, scissors(0.4), 1.0).force_n, force, 0.2 * force);
}

TEST(BladeResistance, ZeroUnlessClosingOnTissue) {
  TetMesh mesh = block();
  BladeResistance b;
  b.update(mesh, table(3e4));
  EXPECT_EQ(b.load(mesh, scissors(1.0), 1.0).torque_nm, 0.0);  // not closing yet
  EXPECT_EQ(b.load(mesh, scissors(1.2), 1.0).torque_nm, 0.0);  // opening
  ToolState away = scissors(0.3);
  away.tip_m[2] = 0.05;  // 4.5 cm above the block
  EXPECT_EQ(b.load(mesh, away, 1.0).torque_nm, 0.0);
  EXPECT_EQ(b.load(mesh, away, 1.0).force_n, 0.0);
  EXPECT_EQ(b.load(mesh, scissors(1.0), 1.0).force_n, 0.0);
}

TEST(BladeResistance, GrowsAsTheBladesCloseAndScalesWithTheModulus) {
  const TetMesh mesh = block();
  BladeResistance soft, stiff;
  soft.update(mesh, table(1e4));
  stiff.update(mesh, table(2e4));
  double prev = 0.0;
  for (double jaw = 1.0; jaw >= 0.0; jaw -= 0.01) {
    const double t = soft.load(mesh, scissors(jaw), 1.0).torque_nm;
    EXPECT_GE(t, prev) << jaw;
    prev = t;
    EXPECT_NEAR(stiff.load(mesh, scissors(jaw), 1.0).torque_nm, 2.0 * t, 1e-12 * t) << jaw;
  }
  EXPECT_GT(prev, 0.0);
}

TEST(BladeResistance, ARigidMotionOfTissueAndScissorsChangesNothing) {
  TetMesh mesh = block();
  BladeResistance b;
  b.update(mesh, table(3e4));
  const double before = b.load(mesh, scissors(0.3), 0.9).torque_nm;
  const Eigen::Quaterniond r(Eigen::AngleAxisd(0.8, Vec3(1, -2, 0.5).normalized()));
  const Vec3 shift(0.1, -0.03, 0.2);
  for (Vec3& x : mesh.x) x = r * x + shift;
  ToolState s = scissors(0.3);
  const Vec3 tip = r * Vec3(s.tip_m[0], s.tip_m[1], s.tip_m[2]) + shift;
  const Eigen::Quaterniond q = r * Eigen::Quaterniond(0.5, 0.5, 0.5, 0.5);
  s.tip_m = {tip.x(), tip.y(), tip.z()};
  s.quat_wxyz = {q.w(), q.x(), q.y(), q.z()};
  EXPECT_NEAR(b.load(mesh, s, 0.9).torque_nm, before, 1e-9 * before);
  EXPECT_GT(before, 0.0);
}

}  // namespace
}  // namespace serosa::contact
