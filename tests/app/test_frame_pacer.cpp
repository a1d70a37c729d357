// FramePacer (window/frame_pacer.h): a solver falling behind makes the window cheaper, rung by rung
// (tessellation first, then resolution, then frame rate), and a solver keeping up brings it back;
// the frame rate never exceeds the cap; a picture too costly for kMinFps steps down the picture's
// rungs alone, and the pacer does not climb back to a rung that drew too slowly.
#include <gtest/gtest.h>

#include <chrono>
#include <vector>

#include "window/frame_pacer.h"

namespace serosa::app {
namespace {

using Clock = window::FramePacer::Clock;
using std::chrono::duration_cast;

Clock::duration sec(double s) {
  return duration_cast<Clock::duration>(std::chrono::duration<double>(s));
}

// Draws frames as the pacer schedules them for `seconds` (each taking `draw_s`), all with the
// solver behind or not; returns the time reached and counts the frames.
Clock::time_point play(window::FramePacer& p, Clock::time_point t, double seconds, bool behind,
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
  window::FramePacer p(3, 60.0);
  Clock::time_point t{};
  int frames = 0;
  t = play(p, t, 2.0, false, 0.001, &frames);
  EXPECT_EQ(p.rung(), 0);
  EXPECT_EQ(p.tessellation(), 3);
  EXPECT_NEAR(frames / 2.0, 60.0, 3.0);  // capped at 60 frames/s with time to spare

  // The solver falls behind: one rung per half second at most, tessellation first, then
  // resolution, then frame rate, to the bottom rung.
  struct Look {
    int tessellation;
    float scale;
    double fps;
  };
  std::vector<Look> seen{{p.tessellation(), p.resolution_scale(), p.max_fps()}};
  const Clock::time_point fall = t;
  for (int k = 0; k < 40; ++k) {
    t = play(p, t, 0.25, true, 0.001);
    const Look l{p.tessellation(), p.resolution_scale(), p.max_fps()};
    if (l.tessellation != seen.back().tessellation || l.scale != seen.back().scale ||
        l.fps != seen.back().fps)
      seen.push_back(l);
  }
  const std::vector<Look> ladder{{3, 1.0f, 60.0},  {2, 1.0f, 60.0}, {1, 1.0f, 60.0},
                                 {1, 0.75f, 60.0}, {1, 0.5f, 60.0}, {1, 0.5f, 30.0},
                                 {1, 0.5f, 15.0},  {1, 0.5f, 8.0}};
  ASSERT_EQ(seen.size(), ladder.size());
  for (std::size_t k = 0; k < ladder.size(); ++k) {
    EXPECT_EQ(seen[k].tessellation, ladder[k].tessellation) << "rung " << k;
    EXPECT_FLOAT_EQ(seen[k].scale, ladder[k].scale) << "rung " << k;
    EXPECT_DOUBLE_EQ(seen[k].fps, ladder[k].fps) << "rung " << k;
  }
  EXPECT_GE(t - fall, sec(0.5 * static_cast<double>(ladder.size() - 1)));  // no faster
  frames = 0;
  t = play(p, t, 2.0, true, 0.001, &frames);
  EXPECT_LE(frames / 2.0, 9.0);  // 8 frames/s
  EXPECT_EQ(p.deepest_rung(), p.rung());
  EXPECT_EQ(p.steps_down(), p.rung());

  // Keeping up again: back up, one rung every three seconds, to the top.
  t = play(p, t, 3.5, false, 0.001);
  EXPECT_EQ(p.rung(), p.deepest_rung() - 1);
  t = play(p, t, 40.0, false, 0.001);
  EXPECT_EQ(p.rung(), 0);
  EXPECT_EQ(p.tessellation(), 3);
  EXPECT_FLOAT_EQ(p.resolution_scale(), 1.0f);
}

TEST(FramePacer, OccasionalLateStepsDoNotStepDown) {
  window::FramePacer p(4, 60.0);
  Clock::time_point t{};
  for (int k = 0; k < 600; ++k) {
    t = std::max(t, p.next_frame()) + sec(0.002);
    p.frame_done(t, k % 10 == 0);  // one frame in ten: under the share
  }
  EXPECT_EQ(p.rung(), 0);
}

TEST(FramePacer, ASlowDrawIsNotCaughtUpAndTheUserMovesTheTop) {
  window::FramePacer p(3, 60.0);
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

// Each frame costs what its tessellation and resolution make it (software GL: 11 frames/s at
// tessellation 3, about 17 at 2): the solver keeps up throughout.
TEST(FramePacer, ATooCostlyPictureStepsDownTheTessellationAndStaysThere) {
  window::FramePacer p(3, 60.0);
  const auto cost = [&p] {
    const double by_level[] = {0.0, 0.04, 0.06, 0.09};
    const auto scale = static_cast<double>(p.resolution_scale());
    return by_level[p.tessellation()] * scale * scale;
  };
  Clock::time_point t{};
  int frames = 0;
  for (int k = 0; k < 300; ++k) {  // 30 s of frames, a tenth of a second at a time
    const Clock::time_point end = t + sec(0.1);
    while (t < end) {
      t = std::max(t, p.next_frame()) + sec(cost());
      p.frame_done(t, false);
      if (k >= 100) ++frames;
    }
    EXPECT_GE(p.max_fps(), 60.0) << "the frame-rate caps are the solver's alone";
    EXPECT_EQ(p.resolution_scale(), 1.0f) << "tessellation 2 is fast enough";
  }
  EXPECT_EQ(p.tessellation(), 2);
  // From the tenth second on: at least kMinFps on average (a retry of level 3 each kRetryS).
  EXPECT_GE(frames / 20.0, window::FramePacer::kMinFps);
}

}  // namespace
}  // namespace serosa::app
