#include "haptics/gap_monitor.h"

#include <pthread.h>
#include <sched.h>
#include <time.h>

#include <algorithm>

#include "haptics/device.h"

namespace serosa::haptics {

std::int64_t monotonic_ns() noexcept {
  timespec ts{};
  clock_gettime(CLOCK_MONOTONIC, &ts);
  return static_cast<std::int64_t>(ts.tv_sec) * 1'000'000'000 + ts.tv_nsec;
}

double monotonic_s() noexcept { return static_cast<double>(monotonic_ns()) * 1e-9; }

bool try_realtime(int priority) noexcept {
  sched_param sp{};
  sp.sched_priority = priority;
  return pthread_setschedparam(pthread_self(), SCHED_FIFO, &sp) == 0;
}

bool pin_to_cpu(int cpu) noexcept {
  if (cpu < 0) return false;
  cpu_set_t set;
  CPU_ZERO(&set);
  CPU_SET(static_cast<unsigned>(cpu), &set);
  return pthread_setaffinity_np(pthread_self(), sizeof(set), &set) == 0;
}

void GapMonitor::start() {
  if (m_thread.joinable()) return;
  m_stop.store(false);
  m_thread = std::thread([this] { run(); });
}

void GapMonitor::stop() {
  m_stop.store(true);
  if (m_thread.joinable()) m_thread.join();
}

void GapMonitor::inject_gap(std::int64_t start_ns, std::int64_t end_ns) noexcept {
  const std::uint64_t i = m_count.load(std::memory_order_relaxed);
  m_start[i % kRing].store(start_ns, std::memory_order_relaxed);
  m_end[i % kRing].store(end_ns, std::memory_order_relaxed);
  m_count.store(i + 1, std::memory_order_release);
}

void GapMonitor::run() {
  if (m_c.realtime) try_realtime(10);
  if (m_c.cpu >= 0) pin_to_cpu(m_c.cpu);
  const auto threshold = static_cast<std::int64_t>(m_c.threshold_s * 1e9);
  const auto poll = static_cast<std::int64_t>(m_c.poll_s * 1e9);
  const timespec req{0, static_cast<long>(poll)};
  std::int64_t prev = monotonic_ns();
  while (!m_stop.load(std::memory_order_relaxed)) {
    if (poll > 0) clock_nanosleep(CLOCK_MONOTONIC, 0, &req, nullptr);
    const std::int64_t now = monotonic_ns();
    if (now - prev > threshold + poll) inject_gap(prev, now);
    prev = now;
  }
}

bool GapMonitor::saw_gap(std::int64_t from_ns, std::int64_t to_ns,
                         std::int64_t min_overlap_ns) const noexcept {
  const std::uint64_t n = m_count.load(std::memory_order_acquire);
  const std::uint64_t look = std::min<std::uint64_t>(n, 64);
  for (std::uint64_t k = 0; k < look; ++k) {
    const std::uint64_t i = (n - 1 - k) % kRing;
    const std::int64_t s = m_start[i].load(std::memory_order_relaxed);
    const std::int64_t e = m_end[i].load(std::memory_order_relaxed);
    const std::int64_t overlap = std::min(e, to_ns) - std::max(s, from_ns);
    if (overlap >= min_overlap_ns) return true;
    if (e < from_ns) break;  // older gaps end even earlier
  }
  return false;
}

}  // namespace serosa::haptics
