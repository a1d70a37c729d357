// FramePacer: the trainee window's renderer gives way to the solver. On two cores the solver
// thread needs one of them whole; a software renderer (Mesa's llvmpipe under Xvfb) would take
// both. So the window draws at most `max_fps`, and when the solver falls behind real time
// (its slow-motion flag, published with each frame) it steps down a ladder of cheaper settings:
// lower tessellation first (the picture's smoothness), then a lower resolution (its sharpness:
// 3/4, then 1/2 of the window's, render/scaled_target.h), then fewer frames per second (its
// fluency), down to tessellation 1 at half resolution and 8 frames/s. A picture too costly to
// draw kMinFps times a second steps down the tessellation and resolution rungs the same way.
// Once the solver has kept up for a while it steps back up, one rung at a time, but not to a
// rung that drew too slowly in the last kRetryS. The solver never waits for the renderer either
// way: it publishes through a triple buffer (engine/triple_buffer.h).
#pragma once

#include <chrono>
#include <cstdint>
#include <optional>
#include <vector>

namespace serosa::window {

class FramePacer {
 public:
  using Clock = std::chrono::steady_clock;

  /// Down after the solver was behind in this share of the frames of a window...
  static constexpr double kBehindShare = 0.25;
  /// ...of this length (also the least time between two steps down), s.
  static constexpr double kWindowS = 0.5;
  /// Up after this long without the solver behind, s.
  static constexpr double kRecoverS = 3.0;
  /// The least frame rate the picture's cost may take the window to, frames/s: below it over a
  /// window the pacer steps down the tessellation and resolution rungs (not the frame-rate caps,
  /// which are the solver's), as if the solver were behind.
  static constexpr double kMinFps = 15.0;
  /// A rung found below kMinFps is not stepped back up to for this long, s.
  static constexpr double kRetryS = 10.0;

  /// tessellation: the level asked for (scene or keys), the top of the ladder; max_fps: the cap
  /// at the top.
  FramePacer(int tessellation, double max_fps = 60.0);

  /// After drawing a frame at `now`: whether the solver was behind (slow motion) in it.
  void frame_done(Clock::time_point now, bool solver_behind);
  /// The user picked another tessellation: the ladder's top moves, the rung stays.
  void set_tessellation(int level);

  /// When to start the next frame (sleep until then).
  [[nodiscard]] Clock::time_point next_frame() const { return m_next; }
  /// The tessellation level to draw with now (<= the one asked for).
  [[nodiscard]] int tessellation() const;
  /// The frame rate cap now, frames/s.
  [[nodiscard]] double max_fps() const;
  /// The fraction of the window's resolution to draw at now, (0, 1].
  [[nodiscard]] float resolution_scale() const;
  /// The rung: 0 at the top (as asked), higher is cheaper.
  [[nodiscard]] int rung() const { return m_rung; }
  /// The cheapest rung reached so far, and the number of steps down.
  [[nodiscard]] int deepest_rung() const { return m_deepest; }
  [[nodiscard]] std::int64_t steps_down() const { return m_downs; }

 private:
  [[nodiscard]] int rungs() const;
  /// Rungs that change the picture (tessellation, resolution), not the frame-rate cap.
  [[nodiscard]] int picture_rungs() const;
  void step_down(Clock::time_point now);
  /// Whether `rung` drew below kMinFps within kRetryS before `now`.
  [[nodiscard]] bool too_slow_since(int rung, Clock::time_point now) const;

  int m_tessellation;
  double m_max_fps;
  int m_rung = 0;
  int m_deepest = 0;
  std::int64_t m_downs = 0;
  Clock::time_point m_next{};
  Clock::time_point m_window_start{};
  Clock::time_point m_last_change{};
  Clock::time_point m_last_behind{};
  // (rungs) when each rung last drew below kMinFps, if it did
  std::vector<std::optional<Clock::time_point>> m_too_slow;
  int m_frames = 0;
  int m_behind = 0;
  bool m_started = false;
};

/// Frames per second as drawn, over windows of about half a second.
class FrameRate {
 public:
  void tick(FramePacer::Clock::time_point now);
  /// The last window's rate, frames/s (0 before the first window ends).
  [[nodiscard]] double hz() const { return m_hz; }

 private:
  FramePacer::Clock::time_point m_start{};
  int m_frames = -1;  // -1: not started
  double m_hz = 0.0;
};

}  // namespace serosa::window
