// The grasp-and-transfer drill's watch (metrics/transfer_watch.h) on a small block carried about
// by hand: hand-offs count only a pass from one grasper to another with no let-go between, a
// let-go away from the target is a drop, and the object is placed when it lies on the target
// held by none; over random sequences of grasps its counts match a plain replay of the rules.
#include <gtest/gtest.h>

#include <random>

#include "engine/kuhn_grid.h"
#include "engine/sim_state.h"
#include "metrics/transfer_watch.h"
#include "support/block_copy.h"

namespace serosa::metrics {
namespace {

constexpr int kBead = 1;
const Vec3 kTarget(0.05, 0.0, 0.0);
constexpr double kRadius = 0.006;

SimState bead(int tools) {
  KuhnGridSpec spec;
  spec.xs = kuhn_axis(3, 0.004);
  spec.ys = kuhn_axis(1, 0.004);
  spec.zs = kuhn_axis(1, 0.004);
  spec.group = [](int, int, int) -> std::uint16_t { return kBead; };
  SimState s;
  s.mesh = kuhn_grid(spec);
  s.tools.resize(static_cast<std::size_t>(tools));
  s.shared.grasped.resize(static_cast<std::size_t>(tools));
  return s;
}

// Moves the bead so that its centre is at c (a rigid shift).
void put(SimState& s, const Vec3& c) {
  Vec3 now = Vec3::Zero();
  for (const Vec3& x : s.mesh.x) now += x;
  now /= static_cast<double>(s.mesh.x.size());
  for (Vec3& x : s.mesh.x) x += c - now;
}

void hold(SimState& s, std::vector<int> tools) {
  for (auto& g : s.shared.grasped) g.clear();
  for (int t : tools) s.shared.grasped[static_cast<std::size_t>(t)] = {0, 1};
}

TEST(TransferWatch, AHandOffADropAndAPlacing) {
  SimState s = bead(3);
  TransferWatch w(kBead, kTarget, kRadius, Vec3::UnitZ());
  double t = 0.0;
  auto step = [&](std::vector<int> holders, const Vec3& at) {
    hold(s, std::move(holders));
    put(s, at);
    w.step(t += 0.005, s);
  };
  const Vec3 away(0.0, 0.0, 0.02), over = kTarget + Vec3(0.002, 0.0, 0.003);
  step({}, Vec3(0.0, 0.0, 0.002));
  step({0}, away);
  step({0, 2}, away);  // the second joins ...
  step({0}, away);     // ... and lets go again: no hand-off
  step({0, 2}, away);
  step({2}, away);  // the first lets go: a hand-off
  EXPECT_EQ(w.handoffs(), 1);
  step({}, away);  // dropped
  EXPECT_EQ(w.drops(), 1);
  step({0}, away);  // picked up again, and straight into the other's jaws after a let-go:
  step({}, away);   // a second drop, no hand-off
  step({2}, away);
  EXPECT_EQ(w.handoffs(), 1);
  EXPECT_EQ(w.drops(), 2);
  step({2}, over);
  EXPECT_FALSE(w.placed());  // still held
  step({}, over);            // let go over the target: not a drop
  EXPECT_EQ(w.drops(), 2);
  EXPECT_TRUE(w.placed());
  EXPECT_NEAR(w.error_m(), 0.002, 1e-12);
  step({}, kTarget + Vec3(0.0, 0.0, 2.0 * kRadius));  // hovering above it is not on it
  EXPECT_FALSE(w.placed());
}

// Random grasps by three graspers, the bead anywhere: the counts are those of the rules replayed
// on the holder sets alone, and a snapshot restores them.
TEST(TransferWatch, RandomGraspSequencesCountAsTheRulesSay) {
  std::mt19937 rng(11);
  std::uniform_real_distribution<double> u(-0.02, 0.02);
  for (int trial = 0; trial < 1000; ++trial) {
    SimState s = bead(3);
    TransferWatch w(kBead, kTarget, kRadius, Vec3::UnitZ());
    std::vector<int> before;
    int sole = -1, handoffs = 0, drops = 0;
    const int n = 1 + static_cast<int>(rng() % 60);
    for (int k = 0; k < n; ++k) {
      std::vector<int> now;
      for (int tool = 0; tool < 3; ++tool)
        if (rng() % 3 == 0) now.push_back(tool);
      const Vec3 at = kTarget + Vec3(u(rng), u(rng), 0.003);
      hold(s, now);
      put(s, at);
      w.step(0.005 * (k + 1), s);
      const double off = Vec3(at.x() - kTarget.x(), at.y() - kTarget.y(), 0.0).norm();
      if (now.empty() && !before.empty() && off > kRadius) ++drops;
      if (now.size() == 1) {
        const bool shared =
            before.size() >= 2 && std::find(before.begin(), before.end(), now[0]) != before.end();
        if (shared && sole >= 0 && sole != now[0]) ++handoffs;
        sole = now[0];
      } else if (now.empty()) {
        sole = -1;
      }
      before = now;
    }
    ASSERT_EQ(w.handoffs(), handoffs) << "trial " << trial;
    ASSERT_EQ(w.drops(), drops) << "trial " << trial;
    TransferWatch back(kBead, kTarget, kRadius, Vec3::UnitZ());
    TransferBlock restored = test_blocks::copy(w.unbound_block());  // (w was never bound)
    back.bind(restored);
    EXPECT_EQ(back.handoffs(), handoffs);
    EXPECT_EQ(back.drops(), drops);
    EXPECT_EQ(back.placed(), w.placed());
    EXPECT_EQ(back.error_m(), w.error_m());
  }
}

}  // namespace
}  // namespace serosa::metrics
