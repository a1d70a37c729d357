// The exchanges read from the inputs' holder bits: the first holds are the start, not
// exchanges; every later change of a hand's instrument is one; time held in a port counts as
// out of the body; a snapshot restores the whole account; two tools claiming one hand do not
// make it flicker.
#include <gtest/gtest.h>

#include <random>

#include "engine/instrument_hold.h"
#include "metrics/hand_exchanges.h"
#include "support/block_copy.h"

namespace serosa::metrics {
namespace {

std::vector<ToolState> hands(std::optional<Hand> a, std::optional<Hand> b, std::optional<Hand> c,
                             bool c_in_port = false) {
  std::vector<ToolState> t(3);
  set_holder(t[0], a);
  set_holder(t[1], b);
  set_holder(t[2], c);
  set_in_port(t[2], c_in_port);
  return t;
}

TEST(HandExchanges, EveryChangeOfAHandsInstrumentAfterTheStartIsOne) {
  HandExchanges x;
  const double dt = 0.005;
  x.step(dt, dt, hands(Hand::kLeft, Hand::kRight, std::nullopt));
  EXPECT_TRUE(x.exchanges().empty());  // the start
  x.step(2 * dt, dt, hands(Hand::kLeft, std::nullopt, Hand::kRight, true));
  x.step(3 * dt, dt, hands(Hand::kLeft, std::nullopt, Hand::kRight, true));
  x.step(4 * dt, dt, hands(Hand::kLeft, std::nullopt, Hand::kRight));
  ASSERT_EQ(x.exchanges().size(), 1u);
  EXPECT_EQ(x.exchanges()[0].hand, 1);
  EXPECT_EQ(x.exchanges()[0].from, 1);
  EXPECT_EQ(x.exchanges()[0].to, 2);
  EXPECT_DOUBLE_EQ(x.exchanges()[0].t_s, 2 * dt);
  EXPECT_DOUBLE_EQ(x.out_of_body_s(), 2 * dt);  // two steps entering through its port
  nlohmann::json j;
  x.report(j, {"grasper", "scissors", "hook"});
  EXPECT_EQ(j["exchanges"][0]["from"], "scissors");
  EXPECT_EQ(j["exchanges"][0]["to"], "hook");
  EXPECT_EQ(j["exchanges"][0]["hand"], "right");
}

TEST(HandExchanges, WithoutHandsThereIsNothingToReport) {
  HandExchanges x;
  for (int k = 1; k < 10; ++k) x.step(k * 0.005, 0.005, std::vector<ToolState>(3));
  nlohmann::json j = nlohmann::json::object();
  x.report(j, {"a", "b", "c"});
  EXPECT_FALSE(x.hands_seen());
  EXPECT_TRUE(j.empty());
}

TEST(HandExchanges, TwoToolsClaimingOneHandLeaveItWithTheOneThatHeldIt) {
  HandExchanges x;
  x.step(0.005, 0.005, hands(Hand::kRight, std::nullopt, std::nullopt));
  x.step(0.010, 0.005, hands(Hand::kRight, std::nullopt, Hand::kRight));
  EXPECT_TRUE(x.exchanges().empty());
  x.step(0.015, 0.005, hands(std::nullopt, std::nullopt, Hand::kRight));
  ASSERT_EQ(x.exchanges().size(), 1u);
  EXPECT_EQ(x.exchanges()[0].to, 2);
}

TEST(HandExchanges, ASnapshotRestoresTheWholeAccount) {
  std::mt19937 rng(9);
  std::uniform_int_distribution<int> pick(0, 3);
  const auto random_hand = [&]() -> std::optional<Hand> {
    const int k = pick(rng);
    return k == 0   ? std::optional<Hand>(Hand::kLeft)
           : k == 1 ? std::optional<Hand>(Hand::kRight)
                    : std::nullopt;
  };
  for (int trial = 0; trial < 200; ++trial) {
    HandExchanges a;
    ExchangesBlock state_a;
    a.bind(state_a);
    for (int k = 1; k <= 20; ++k)
      a.step(k * 0.005, 0.005, hands(random_hand(), random_hand(), random_hand(), pick(rng) == 0));
    HandExchanges b;
    ExchangesBlock state_b = test_blocks::copy(state_a);
    b.bind(state_b);
    for (int k = 21; k <= 40; ++k) {
      const auto t = hands(random_hand(), random_hand(), random_hand(), pick(rng) == 0);
      a.step(k * 0.005, 0.005, t);
      b.step(k * 0.005, 0.005, t);
    }
    nlohmann::json ja, jb;
    a.report(ja, {"a", "b", "c"});
    b.report(jb, {"a", "b", "c"});
    EXPECT_EQ(ja, jb) << trial;
  }
}

}  // namespace
}  // namespace serosa::metrics
