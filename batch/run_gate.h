// Lets a batch's ordinary runs share the machine and a paced run (a rig in the loop, stepping at
// the wall clock's pace) have it alone: a paced run waits for the runs in progress to end, and no
// run starts while a paced one waits or runs.
#pragma once

#include <condition_variable>
#include <mutex>

namespace serosa::batch {

class RunGate {
 public:
  /// Blocks until the run may start: `alone` when nothing else runs, otherwise when no paced run
  /// runs or waits.
  void enter(bool alone);
  /// The run started with enter(alone) has ended.
  void leave(bool alone);

 private:
  std::mutex m_mutex;
  std::condition_variable m_changed;
  int m_shared = 0;         ///< ordinary runs in progress
  int m_waiting_alone = 0;  ///< paced runs waiting to start
  bool m_alone = false;     ///< a paced run in progress
};

}  // namespace serosa::batch
