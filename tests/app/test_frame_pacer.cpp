// FramePacer (app/frame_pacer.h): a solver falling behind makes the window cheaper, rung by rung
// (tessellation first, then frame rate), and a solver keeping up brings it back; the frame rate
// never exceeds the cap.
#include <gtest/gtest.h>

#include <chrono>

#include "app/frame_pacer.h"

namespace serosa::app {
namespace {

using Clock = FramePacer::Clock;
using std::chrono::duration_cast;

Clock::duration sec(double s) {
  return duration_cast<Clock::duration>(std::chrono::duration<double>(s));
}

// Draws frames as the pacer schedules them for `seconds` (each taking `draw_s`), all with the
// solver behind or not; returns the time reached and counts the frames.
Clock::time_point play(FramePacer& p, Clock::time_point t, double seconds, bool behind,
                       double draw_s, int* frames = nullptr) {
  const Clock::time_point end = t + sec(seconds);
  while (t < end) {
    t = std::max(t, p.next_frame()) + sec(draw_s);
    p.frame_done(t, behind);
    if (frames != nullptr) ++*frames;
  }
  return t;
}

TEST(FramePacer, BehindStepsDownTessellationThenFrameRateAndRecovers) {
  FramePacer p(3, 60.0);
  Clock::time_point t{};
  int frames = 0;
  t = play(p, t, 2.0, false, 0.001, &frames);
  EXPECT_EQ(p.rung(), 0);
  EXPECT_EQ(p.tessellation(), 3);
  EXPECT_NEAR(frames / 2.0, 60.0, 3.0);  // capped at 60 frames/s with time to spare

  // The solver falls behind: one rung per half second, tessellation first.
  t = play(p, t, 0.6, true, 0.001);
  EXPECT_EQ(p.rung(), 1);
  EXPECT_EQ(p.tessellation(), 2);
  EXPECT_DOUBLE_EQ(p.max_fps(), 60.0);
  t = play(p, t, 1.0, true, 0.001);
  EXPECT_EQ(p.tessellation(), 1);
  t = play(p, t, 3.0, true, 0.001);
  EXPECT_EQ(p.tessellation(), 1);
  EXPECT_LT(p.max_fps(), 60.0);
  frames = 0;
  t = play(p, t, 2.0, true, 0.001, &frames);
  EXPECT_DOUBLE_EQ(p.max_fps(), 8.0);  // the bottom rung
  EXPECT_LE(frames / 2.0, 16.0);
  EXPECT_EQ(p.deepest_rung(), p.rung());
  EXPECT_EQ(p.steps_down(), p.rung());

  // Keeping up again: back up, one rung every three seconds, to the top.
  t = play(p, t, 3.5, false, 0.001);
  EXPECT_EQ(p.rung(), p.deepest_rung() - 1);
  t = play(p, t, 30.0, false, 0.001);
  EXPECT_EQ(p.rung(), 0);
  EXPECT_EQ(p.tessellation(), 3);
}

TEST(FramePacer, OccasionalLateStepsDoNotStepDown) {
  FramePacer p(4, 60.0);
  Clock::time_point t{};
  for (int k = 0; k < 600; ++k) {
    t = std::max(t, p.next_frame()) + sec(0.002);
    p.frame_done(t, k % 10 == 0);  // one frame in ten: under the share
  }
  EXPECT_EQ(p.rung(), 0);
}

TEST(FramePacer, ASlowDrawIsNotCaughtUpAndTheUserMovesTheTop) {
  FramePacer p(3, 60.0);
  Clock::time_point t{};
  p.frame_done(t + sec(0.2), false);  // one frame took 200 ms
  EXPECT_LE(p.next_frame() - (t + sec(0.2)), sec(1.0 / 60.0) + sec(1e-9));
  // Down two rungs, then the user asks for tessellation 6: still two levels under the top.
  t = play(p, t + sec(0.2), 1.2, true, 0.001);
  ASSERT_EQ(p.tessellation(), 1);
  p.set_tessellation(6);
  EXPECT_EQ(p.tessellation(), 4);
  p.set_tessellation(1);
  EXPECT_EQ(p.tessellation(), 1);
}

}  // namespace
}  // namespace serosa::app
