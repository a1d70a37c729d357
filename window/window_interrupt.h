// Ctrl-C or SIGTERM while a window is open: the window's loop ends at its next frame and closes
// what it recorded, instead of the process dying with the recording half written.
#pragma once

#include <atomic>

namespace serosa::window {

/// Installs the SIGINT/SIGTERM handler for its lifetime (clearing the flag) and restores the
/// previous handlers after. A signal handler can reach no other state, so the flag it sets is
/// process-wide; use one guard at a time.
class InterruptGuard {
 public:
  InterruptGuard();
  ~InterruptGuard();
  InterruptGuard(const InterruptGuard&) = delete;
  InterruptGuard& operator=(const InterruptGuard&) = delete;

  /// True once a signal arrived since the guard was made.
  [[nodiscard]] bool interrupted() const;
  /// The flag itself, for loops that take it by reference.
  [[nodiscard]] const std::atomic<bool>& flag() const;

 private:
  void (*m_int)(int);
  void (*m_term)(int);
};

}  // namespace serosa::window
