// SnapshotSink: where the runner hands the whole state every so many steps (Runner::
// record_snapshots). The engine knows only this; the recording writer (recording/) is one.
#pragma once

#include <cstdint>
#include <span>

namespace serosa {

class SnapshotSink {
 public:
  virtual ~SnapshotSink() = default;
  /// The whole state after `steps` steps (Runner::snapshot's bytes).
  virtual void record_snapshot(std::uint64_t steps, std::span<const std::uint8_t> snapshot) = 0;

 protected:
  SnapshotSink() = default;
  SnapshotSink(const SnapshotSink&) = default;
  SnapshotSink& operator=(const SnapshotSink&) = default;
};

}  // namespace serosa
