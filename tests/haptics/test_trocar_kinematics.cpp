// Trocar kinematics: round trips, Jacobian against finite differences, lever ratio, pivot
// singularity.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <random>

#include "haptics/random_trocars.h"
#include "haptics/trocar_kinematics.h"

namespace serosa::haptics {
namespace {

Vec3 tip_of(const ToolState& s) { return {s.tip_m[0], s.tip_m[1], s.tip_m[2]}; }

TEST(TrocarKinematics, ZeroJointsPointAlongTrocarAxis) {
  Trocar t;
  t.pivot_m = Vec3(0.1, 0.2, 0.3);
  JointState q;
  q.insertion_m = 0.05;
  const ToolState s = forward(t, q);
  EXPECT_NEAR((tip_of(s) - Vec3(0.1, 0.2, 0.35)).norm(), 0.0, 1e-15);
}

TEST(TrocarKinematics, ForwardInverseRoundTrip) {
  std::mt19937 rng(7);
  for (int i = 0; i < 2000; ++i) {
    const Trocar t = random_trocar(rng);
    const JointState q = random_joints(rng);
    const ToolState s = forward(t, q);
    const JointState r = inverse(t, s);
    ASSERT_NEAR(r.pitch_rad, q.pitch_rad, 1e-9) << i;
    ASSERT_NEAR(std::remainder(r.yaw_rad - q.yaw_rad, 2 * std::numbers::pi), 0.0, 1e-9) << i;
    ASSERT_NEAR(std::remainder(r.roll_rad - q.roll_rad, 2 * std::numbers::pi), 0.0, 1e-9) << i;
    ASSERT_NEAR(r.insertion_m, q.insertion_m, 1e-12) << i;
    ASSERT_EQ(r.jaw_rad, q.jaw_rad);
    // The tip lies on the line through the pivot: distance equals insertion.
    ASSERT_NEAR((tip_of(s) - t.pivot_m).norm(), q.insertion_m, 1e-12);
    // And inverse_from_tip recovers pitch, yaw, insertion.
    const JointState p = inverse_from_tip(t, tip_of(s), JointState{});
    if (q.insertion_m > 1e-6) {
      ASSERT_NEAR(p.pitch_rad, q.pitch_rad, 1e-6);
      ASSERT_NEAR(std::remainder(p.yaw_rad - q.yaw_rad, 2 * std::numbers::pi), 0.0, 1e-6);
      ASSERT_NEAR(p.insertion_m, q.insertion_m, 1e-12);
    }
  }
}

TEST(TrocarKinematics, SingularInsertionZero) {
  std::mt19937 rng(8);
  for (int i = 0; i < 200; ++i) {
    const Trocar t = random_trocar(rng);
    JointState q = random_joints(rng);
    q.insertion_m = 0.0;
    const ToolState s = forward(t, q);
    EXPECT_NEAR((tip_of(s) - t.pivot_m).norm(), 0.0, 1e-15);
    // The full pose still determines the angles at the pivot.
    const JointState r = inverse(t, s);
    EXPECT_NEAR(r.pitch_rad, q.pitch_rad, 1e-9);
    EXPECT_NEAR(r.insertion_m, 0.0, 1e-15);
    // Tip only: the direction is undefined; the previous one is kept, no NaN.
    JointState prev = random_joints(rng);
    const JointState p = inverse_from_tip(t, t.pivot_m, prev);
    EXPECT_EQ(p.pitch_rad, prev.pitch_rad);
    EXPECT_EQ(p.yaw_rad, prev.yaw_rad);
    EXPECT_EQ(p.insertion_m, 0.0);
    // Efforts at the pivot: a tip force causes no pitch/yaw torque, only the axial force.
    const Vec3 f(1.0, -2.0, 0.5);
    const JointEffort e = tip_to_joint(t, q, f);
    EXPECT_EQ(e.pitch_Nm, 0.0);
    EXPECT_EQ(e.yaw_Nm, 0.0);
    EXPECT_TRUE(std::isfinite(e.insertion_N));
    const Vec3 h = tip_to_handle_force(t, q, f);
    EXPECT_TRUE(h.allFinite());
  }
  // NaN tip input keeps the previous joints finite.
  const JointState p = inverse_from_tip(Trocar{}, Vec3(std::nan(""), 0, 0), JointState{});
  EXPECT_TRUE(std::isfinite(p.insertion_m));
}

TEST(TrocarKinematics, JacobianMatchesFiniteDifferences) {
  std::mt19937 rng(9);
  for (int i = 0; i < 300; ++i) {
    const Trocar t = random_trocar(rng);
    const JointState q = random_joints(rng);
    const Mat3 j = tip_jacobian(t, q);
    const double h = 1e-6;
    for (int c = 0; c < 3; ++c) {
      JointState qp = q;
      JointState qm = q;
      double* fp = c == 0 ? &qp.pitch_rad : c == 1 ? &qp.yaw_rad : &qp.insertion_m;
      double* fm = c == 0 ? &qm.pitch_rad : c == 1 ? &qm.yaw_rad : &qm.insertion_m;
      *fp += h;
      *fm -= h;
      const Vec3 fd = (tip_of(forward(t, qp)) - tip_of(forward(t, qm))) / (2 * h);
      ASSERT_NEAR((fd - j.col(c)).norm(), 0.0, 1e-7) << "column " << c;
    }
  }
}

TEST(TrocarKinematics, EffortsDoVirtualWork) {
  // tau . dq == F . dtip for small joint motions (power balance).
  std::mt19937 rng(10);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  for (int i = 0; i < 300; ++i) {
    const Trocar t = random_trocar(rng);
    const JointState q = random_joints(rng);
    const Vec3 f(u(rng), u(rng), u(rng));
    const JointEffort e = tip_to_joint(t, q, f);
    const Vec3 dq(u(rng), u(rng), u(rng));
    const Vec3 dtip = tip_jacobian(t, q) * dq;
    EXPECT_NEAR(e.pitch_Nm * dq.x() + e.yaw_Nm * dq.y() + e.insertion_N * dq.z(), f.dot(dtip),
                1e-12);
  }
}

TEST(TrocarKinematics, LeverRatioAndMomentBalance) {
  std::mt19937 rng(11);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  for (int i = 0; i < 500; ++i) {
    const Trocar t = random_trocar(rng);
    const JointState q = random_joints(rng);
    const Vec3 d = (tip_of(forward(t, q)) - t.pivot_m).normalized();
    const Vec3 f(u(rng), u(rng), u(rng));
    const Vec3 lateral = f - f.dot(d) * d;
    const Vec3 h = tip_to_handle_force(t, q, f);
    const Vec3 h_lat = h - h.dot(d) * d;
    // Lateral: reversed and scaled by insertion / handle length.
    EXPECT_NEAR((h_lat + (q.insertion_m / t.handle_length_m) * lateral).norm(), 0.0, 1e-12);
    // Axial: passed through.
    EXPECT_NEAR(h.dot(d), f.dot(d), 1e-12);
    // The handle force at -handle_length*d has the same moment about the pivot as F at the tip.
    const Vec3 m_handle = (-t.handle_length_m * d).cross(h);
    EXPECT_NEAR((m_handle - pivot_moment(t, q, f)).norm(), 0.0, 1e-12);
  }
  // Concrete numbers: 1 N lateral at 10 cm insertion, 20 cm handle -> 0.5 N at the hand.
  Trocar t;
  t.handle_length_m = 0.2;
  JointState q;
  q.insertion_m = 0.1;
  const Vec3 h = tip_to_handle_force(t, q, Vec3(1.0, 0.0, 0.0));
  EXPECT_NEAR(h.x(), -0.5, 1e-15);
  const JointEffort e = tip_to_joint(t, q, Vec3(1.0, 0.0, 0.0));
  EXPECT_NEAR(e.yaw_Nm, 0.1, 1e-15);  // 1 N x 0.1 m about the yaw axis
}

TEST(TrocarKinematics, RollTorqueFromTipMoment) {
  Trocar t;
  JointState q;
  q.insertion_m = 0.1;
  q.pitch_rad = 0.3;
  const Vec3 shaft = tool_rotation(t, q) * Vec3::UnitZ();
  const JointEffort e = tip_to_joint(t, q, Vec3::Zero(), 0.02 * shaft, 0.01);
  EXPECT_NEAR(e.roll_Nm, 0.02, 1e-15);
  EXPECT_EQ(e.jaw_Nm, 0.01);
}

}  // namespace
}  // namespace serosa::haptics
