// The procedure's run split at its steps (metrics/step_splits.h) and where the clips went
// (metrics/clip_placement.h), over random runs: the splits add up to the whole run, each step's
// split is what happened since the step done before it, and a snapshot restores them exactly.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <numeric>
#include <random>

#include "metrics/clip_placement.h"
#include "metrics/step_splits.h"
#include "support/block_copy.h"

namespace serosa::metrics {
namespace {

constexpr double kDt = 0.005;  // s

TEST(StepSplits, RandomRunsAddUpToTheWholeRunAndSplitWhereStepsAreDone) {
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> move(0.0, 1e-3);  // m a step
  for (int trial = 0; trial < 2000; ++trial) {
    const std::size_t steps = 5;
    StepSplits s(steps, {"scope", "left", "right"}, {0, 1, 1});
    std::vector<double> total(3, 0.0), since(3, 0.0);
    double since_s = 0.0, idle_since = 0.0;
    const int n = 1 + static_cast<int>(rng() % 400);
    std::vector<bool> done(steps, false);
    std::vector<double> want_duration(steps, 0.0), want_hands(steps, 0.0), want_idle(steps, 0.0);
    for (int k = 0; k < n; ++k) {
      std::vector<double> moved(3);
      for (double& m : moved) m = rng() % 3 == 0 ? 0.0 : move(rng);
      const bool idle = moved[1] == 0.0 && moved[2] == 0.0;
      s.add(moved, idle, kDt);
      for (std::size_t i = 0; i < 3; ++i) total[i] += moved[i], since[i] += moved[i];
      since_s += kDt;
      idle_since += idle ? kDt : 0.0;
      // Now and then one or two steps are done, in any order, never twice.
      for (int c = 0; c < 2 && rng() % 25 == 0; ++c) {
        const std::size_t i = rng() % steps;
        if (done[i]) continue;
        done[i] = true;
        s.close(i);
        want_duration[i] = since_s, want_hands[i] = since[1] + since[2], want_idle[i] = idle_since;
        std::fill(since.begin(), since.end(), 0.0);
        since_s = idle_since = 0.0;
      }
    }
    double duration = s.open().duration_s, hands = s.hand_path_m(s.open());
    for (std::size_t i = 0; i < steps; ++i) {
      EXPECT_NEAR(s.split(i).duration_s, want_duration[i], 1e-12);
      EXPECT_NEAR(s.hand_path_m(s.split(i)), want_hands[i], 1e-12);
      EXPECT_NEAR(s.split(i).idle_s, want_idle[i], 1e-12);
      duration += s.split(i).duration_s;
      hands += s.hand_path_m(s.split(i));
    }
    ASSERT_NEAR(duration, n * kDt, 1e-9) << "trial " << trial;
    ASSERT_NEAR(hands, total[1] + total[2], 1e-12) << "trial " << trial;
    EXPECT_NEAR(s.open().duration_s, since_s, 1e-12);

    // A snapshot restores every split.
    StepSplits back(steps, {"scope", "left", "right"}, {0, 1, 1});
    SplitsBlock restored = test_blocks::copy(s.unbound_block());  // (s was never bound)
    back.bind(restored);
    nlohmann::json a{{"procedure", {{"steps", nlohmann::json::array()}}}}, b = a;
    for (std::size_t i = 0; i < steps; ++i) {
      a["procedure"]["steps"].push_back(nlohmann::json::object());
      b["procedure"]["steps"].push_back(nlohmann::json::object());
    }
    s.report(a);
    back.report(b);
    ASSERT_EQ(a, b);
  }
}

Clip clip_on(std::vector<int> groups, Vec3 centre, Clip::Kind kind = Clip::Kind::kClip) {
  Clip c;
  c.kind = kind;
  c.groups = std::move(groups);
  c.rest_centre_m = centre;
  return c;
}

TEST(ClipPlacement, CountsClipsOnAndOffTheArteryAndTheNearestToTheTarget) {
  constexpr int kArtery = 4, kFold = 2;
  ClipPlacement p(kArtery, Vec3(0.01, 0.0, 0.0));
  p.step({});
  EXPECT_EQ(p.on_artery(), 0);
  EXPECT_TRUE(std::isinf(p.target_error_m()));  // no clip on the artery: infinitely far
  p.step({clip_on({kFold}, Vec3::Zero()), clip_on({kFold, kArtery}, Vec3(0.013, 0.004, 0.0)),
          clip_on({kArtery}, Vec3(0.01, 0.0, 0.002)),
          clip_on({kArtery}, Vec3(0.01, 0.0, 0.0), Clip::Kind::kLoop)});
  EXPECT_EQ(p.on_artery(), 2);
  EXPECT_EQ(p.off_artery(), 1);
  EXPECT_NEAR(p.target_error_m(), 0.002, 1e-15);  // the loop does not count
  nlohmann::json j;
  p.report(j);
  EXPECT_EQ(j["clips"]["on_artery"], 2);
  EXPECT_NEAR(j["clips"]["target_error_m"].get<double>(), 0.002, 1e-15);

  ClipPlacement back(kArtery, Vec3(0.01, 0.0, 0.0));
  ClipPlacementBlock restored = test_blocks::copy(p.unbound_block());  // (p was never bound)
  back.bind(restored);
  EXPECT_EQ(back.on_artery(), 2);
  EXPECT_EQ(back.off_artery(), 1);
  EXPECT_EQ(back.target_error_m(), p.target_error_m());
}

}  // namespace
}  // namespace serosa::metrics
