#include "window/frame_pacer.h"

#include <algorithm>
#include <array>

namespace serosa::window {
namespace {

// Below tessellation 1: the resolution scales, then the frame-rate caps (frames/s).
constexpr std::array<float, 2> kScales{0.75f, 0.5f};
constexpr std::array<double, 3> kSlowFps{30.0, 15.0, 8.0};

double seconds(FramePacer::Clock::duration d) { return std::chrono::duration<double>(d).count(); }

}  // namespace

FramePacer::FramePacer(int tessellation, double max_fps)
    : m_tessellation(std::max(tessellation, 1)), m_max_fps(std::max(max_fps, 1.0)) {}

// Rungs: 0 .. tessellation - 1 lower the tessellation one level each (at max_fps); then the
// resolution scales and the slow frame rates at tessellation 1.
int FramePacer::rungs() const {
  return m_tessellation + static_cast<int>(kScales.size() + kSlowFps.size());
}

int FramePacer::picture_rungs() const { return m_tessellation + static_cast<int>(kScales.size()); }

bool FramePacer::too_slow_since(int rung, Clock::time_point now) const {
  const auto& at = m_too_slow[static_cast<std::size_t>(rung)];
  return at && seconds(now - *at) < kRetryS;
}

void FramePacer::step_down(Clock::time_point now) {
  ++m_rung;
  ++m_downs;
  m_deepest = std::max(m_deepest, m_rung);
  m_last_change = now;
}

float FramePacer::resolution_scale() const {
  const int below = m_rung - (m_tessellation - 1);  // rungs below tessellation 1
  if (below <= 0) return 1.0f;
  return kScales[static_cast<std::size_t>(std::min(below, static_cast<int>(kScales.size())) - 1)];
}

int FramePacer::tessellation() const { return std::max(m_tessellation - m_rung, 1); }

double FramePacer::max_fps() const {
  const int slow = m_rung - (m_tessellation - 1) - static_cast<int>(kScales.size());
  if (slow <= 0) return m_max_fps;
  return std::min(m_max_fps, kSlowFps[static_cast<std::size_t>(slow - 1)]);
}

// The rung keeps its distance below the top (the user's level), and a slowed frame rate stays.
void FramePacer::set_tessellation(int level) {
  const int slow = std::max(m_rung - (m_tessellation - 1), 0);
  m_tessellation = std::max(level, 1);
  m_rung = slow > 0 ? m_tessellation - 1 + slow : std::min(m_rung, m_tessellation - 1);
}

void FramePacer::frame_done(Clock::time_point now, bool solver_behind) {
  if (!m_started) {
    m_started = true;
    m_window_start = m_last_change = m_last_behind = now;
  }
  ++m_frames;
  if (solver_behind) {
    ++m_behind;
    m_last_behind = now;
  }
  m_too_slow.resize(static_cast<std::size_t>(rungs()));
  if (const double window = seconds(now - m_window_start); window >= kWindowS) {
    const bool behind = m_behind > kBehindShare * m_frames;
    const bool slow = m_frames < kMinFps * window && m_rung < picture_rungs();
    if (slow) m_too_slow[static_cast<std::size_t>(m_rung)] = now;
    const bool down = behind ? m_rung + 1 < rungs() : slow && m_rung + 1 < picture_rungs();
    if (down && seconds(now - m_last_change) >= kWindowS) step_down(now);
    m_window_start = now;
    m_frames = m_behind = 0;
  }
  if (m_rung > 0 && seconds(now - m_last_behind) >= kRecoverS &&
      seconds(now - m_last_change) >= kRecoverS && !too_slow_since(m_rung - 1, now)) {
    --m_rung;
    m_last_change = now;
  }
  const auto interval =
      std::chrono::duration_cast<Clock::duration>(std::chrono::duration<double>(1.0 / max_fps()));
  // From the last frame's due time, unless that is already past (a slow frame: no catch-up).
  m_next = std::max(m_next + interval, now);
  if (m_next > now + interval) m_next = now + interval;
}

void FrameRate::tick(FramePacer::Clock::time_point now) {
  if (m_frames < 0) {
    m_start = now;
    m_frames = 0;
    return;
  }
  ++m_frames;
  const double s = seconds(now - m_start);
  if (s < 0.5) return;
  m_hz = m_frames / s;
  m_start = now;
  m_frames = 0;
}

}  // namespace serosa::window
