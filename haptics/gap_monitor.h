// GapMonitor: a thread that reads CLOCK_MONOTONIC every poll_s (poll mode, default 100 us, at a
// SCHED_FIFO priority below the loop's, on the loop's core) or in a tight loop (poll_s = 0, spin
// mode: costs a whole core) and records every interval longer than threshold_s: times when this
// thread did not run at all. The host of these VMs pauses guests now and then (2-20 ms measured);
// when the 1 kHz loop is late and the monitor saw a gap over the same interval, the lateness was
// the platform's (a stall), otherwise it was the loop's own overrun. Lock-free: gaps go into a
// fixed ring.
#pragma once

#include <array>
#include <atomic>
#include <cstdint>
#include <thread>

namespace serosa::haptics {

struct GapMonitorConfig {
  double threshold_s = 0.15e-3;  ///< an interval longer than this (beyond the poll sleep) is a gap
  double poll_s = 100e-6;        ///< 0: spin; > 0: sleep this long between clock reads
  bool realtime = true;          ///< try SCHED_FIFO (priority below the loop's)
  int cpu = -1;                  ///< pin to this core (-1: no pinning)
};

class GapMonitor {
 public:
  explicit GapMonitor(const GapMonitorConfig& c = {}) : m_c(c) {}
  GapMonitor(const GapMonitor&) = delete;
  GapMonitor& operator=(const GapMonitor&) = delete;
  ~GapMonitor() { stop(); }

  void start();
  void stop();
  [[nodiscard]] bool running() const noexcept { return m_thread.joinable(); }

  /// True if a recorded gap overlaps [from_ns, to_ns] (CLOCK_MONOTONIC ns) by at least
  /// min_overlap_ns. Lock-free, callable from the loop.
  [[nodiscard]] bool saw_gap(std::int64_t from_ns, std::int64_t to_ns,
                             std::int64_t min_overlap_ns) const noexcept;
  /// Gaps recorded so far.
  [[nodiscard]] std::uint64_t gaps() const noexcept {
    return m_count.load(std::memory_order_acquire);
  }
  /// Test hook: records a gap as if the thread had observed it.
  void inject_gap(std::int64_t start_ns, std::int64_t end_ns) noexcept;

 private:
  static constexpr std::size_t kRing = 1024;
  void run();

  GapMonitorConfig m_c;
  std::thread m_thread;
  std::atomic<bool> m_stop{false};
  std::array<std::atomic<std::int64_t>, kRing> m_start{};
  std::array<std::atomic<std::int64_t>, kRing> m_end{};
  std::atomic<std::uint64_t> m_count{0};
};

/// CLOCK_MONOTONIC in ns.
[[nodiscard]] std::int64_t monotonic_ns() noexcept;

/// Tries SCHED_FIFO at `priority` for the calling thread; true if granted.
bool try_realtime(int priority) noexcept;
/// Pins the calling thread to `cpu`; true on success.
bool pin_to_cpu(int cpu) noexcept;

}  // namespace serosa::haptics
