// KeyClock (render/key_clock.h): key events come in batches, one poll a frame, and their own
// times are lost. Over thousands of random frame schedules (1 ms to 0.6 s a frame) and key
// presses (taps of a few ms, holds of seconds), the time a release reports is never longer than
// the key was really down, and never shorter by more than the two frames around it. So a tap
// stays a tap however slow the frames, and a hold is not mistaken for a tap.
#include <gtest/gtest.h>

#include <algorithm>
#include <random>
#include <vector>

#include "render/key_clock.h"

namespace serosa::render {
namespace {

// Polls at `polls` (s, increasing); the key really goes down at `down` and up at `up`.
// Returns what the release reported and the longest frame around the press and the release.
struct Measured {
  double held_s = -1.0;
  double frame_s = 0.0;
};
Measured measure(const std::vector<double>& polls, double down, double up) {
  KeyClock clock(1);
  Measured m;
  bool pressed = false;
  for (std::size_t i = 0; i < polls.size(); ++i) {
    clock.poll(polls[i]);
    const double gap = i == 0 ? 0.0 : polls[i] - polls[i - 1];
    // What came in since the previous poll is delivered now, in order.
    if (!pressed && down <= polls[i]) {
      clock.press(0);
      pressed = true;
      m.frame_s = std::max(m.frame_s, gap);
    }
    if (pressed && up <= polls[i]) {
      m.held_s = clock.release(0);
      m.frame_s = std::max(m.frame_s, gap);
      return m;
    }
  }
  return m;
}

TEST(KeyClock, AReleaseNeverReportsLongerThanTheKeyWasDown) {
  std::mt19937 rng(38);
  std::uniform_real_distribution<double> frame(0.001, 0.6), start(0.0, 3.0);
  std::uniform_real_distribution<double> tap(0.0, 0.03), hold(0.3, 3.0);
  for (int trial = 0; trial < 5000; ++trial) {
    std::vector<double> polls{0.0};
    while (polls.back() < 10.0) polls.push_back(polls.back() + frame(rng));
    const double down = start(rng);
    const double up = down + (trial % 2 == 0 ? tap(rng) : hold(rng));
    const Measured m = measure(polls, down, up);
    ASSERT_GE(m.held_s, 0.0) << "trial " << trial;
    EXPECT_LE(m.held_s, up - down + 1e-12) << "trial " << trial;
    EXPECT_GE(m.held_s, up - down - 2.0 * m.frame_s - 1e-12) << "trial " << trial;
  }
}

TEST(KeyClock, ATapSplitByASlowFrameIsATap) {
  KeyClock clock(2);
  clock.poll(1.0);
  clock.press(1);  // delivered by the poll at 1.0 s ...
  EXPECT_NEAR(clock.held_s(1, 1.5), 0.5, 1e-12);
  clock.poll(1.5);  // ... its release by the next, after a 0.5 s frame
  EXPECT_EQ(clock.release(1), 0.0);
  EXPECT_LT(clock.held_s(1, 2.0), 0.0);  // up
  EXPECT_LT(clock.release(1), 0.0);      // a release without a press is not a hold
  EXPECT_LT(clock.release(7), 0.0);      // nor is a key it does not know
}

TEST(KeyClock, AKeyRepeatDoesNotRestartTheHold) {
  KeyClock clock(1);
  clock.poll(0.0);
  clock.press(0);
  for (double t = 0.1; t < 1.05; t += 0.1) {
    clock.poll(t);
    clock.press(0);
  }
  clock.poll(1.1);
  EXPECT_NEAR(clock.release(0), 1.0, 1e-9);
}

}  // namespace
}  // namespace serosa::render
