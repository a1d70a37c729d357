// RecordingWriter: the solver hands it what it consumed each step; a writer thread turns that
// into checksummed chunks of a .lapr file (recording/recording_format.h), flushed at least every
// `flush_interval` (default 0.2 s), so a crash or kill -9 loses at most that much of the run.
//
// The solver side (record_inputs, record_hash, record_event) only appends bytes to a buffer under
// a mutex, never touching the file; the writer thread swaps the buffer out and writes it.
#pragma once

#include <chrono>
#include <condition_variable>
#include <cstdint>
#include <cstdio>
#include <deque>
#include <filesystem>
#include <mutex>
#include <span>
#include <string>
#include <thread>
#include <vector>

#include "engine/snapshot_sink.h"
#include "engine/tool_state.h"
#include "recording/recording_format.h"

namespace serosa::recording {

struct WriterOptions {
  /// Longest time a recorded step waits before it is written and flushed to the OS.
  std::chrono::milliseconds flush_interval{200};
  /// A chunk is also written when this many bytes are pending.
  std::size_t chunk_bytes = 1u << 20;
};

struct WriterStats {
  std::uint64_t chunks = 0;     ///< chunks written
  std::uint64_t bytes = 0;      ///< bytes written, header included
  std::uint64_t steps = 0;      ///< input records taken
  std::uint64_t snapshots = 0;  ///< snapshot records taken
};

class RecordingWriter final : public SnapshotSink {
 public:
  /// Creates (truncates) `path`, writes the header and starts the writer thread. Throws
  /// std::runtime_error naming the file when it cannot be created or written.
  RecordingWriter(const std::filesystem::path& path, const Header& header,
                  WriterOptions options = {});
  /// Same as close() (errors are swallowed here; call close() to see them).
  ~RecordingWriter() override;
  RecordingWriter(const RecordingWriter&) = delete;
  RecordingWriter& operator=(const RecordingWriter&) = delete;

  /// The tool inputs the solver consumed in step `step` (scene tool order).
  void record_inputs(std::uint64_t step, std::span<const ToolState> tools);
  /// The state hash after step `step`.
  void record_hash(std::uint64_t step, std::uint64_t hash);
  /// The whole state after `steps` steps (Runner::snapshot). A snapshot too large for one chunk
  /// is left out, with an event saying so (the replay then starts from an earlier one).
  void record_snapshot(std::uint64_t steps, std::span<const std::uint8_t> snapshot) override;
  /// A named event at step `step` (e.g. "pause", "branch").
  void record_event(std::uint64_t step, const std::string& text);

  /// Writes what is pending plus an end record (`steps` taken in all), stops the thread and
  /// closes the file. Idempotent. Throws std::runtime_error on a write error.
  void close(std::uint64_t steps);
  /// Stops without an end record (the file then reads as cut short at its last chunk).
  void abandon();

  [[nodiscard]] WriterStats stats() const;
  [[nodiscard]] const std::filesystem::path& path() const noexcept { return m_path; }

 private:
  void run();
  void write_chunk(std::vector<std::uint8_t>& payload);  // writer thread (or close) only
  void stop(bool with_end, std::uint64_t steps);

  std::filesystem::path m_path;
  WriterOptions m_options;
  std::FILE* m_file = nullptr;
  mutable std::mutex m_mutex;
  std::condition_variable m_wake;
  std::vector<std::uint8_t> m_pending;  // guarded by m_mutex
  /// Payloads that reached chunk_bytes, in order, each to become one chunk; guarded by m_mutex.
  std::deque<std::vector<std::uint8_t>> m_ready;
  void seal_if_full();  // caller holds m_mutex
  bool m_stop = false;  // guarded by m_mutex
  std::string m_error;  // guarded by m_mutex
  WriterStats m_stats;  // guarded by m_mutex
  std::thread m_thread;
  bool m_closed = false;
};

}  // namespace serosa::recording
