#include "recording/recording_writer.h"

#include <stdexcept>

namespace serosa::recording {

RecordingWriter::RecordingWriter(const std::filesystem::path& path, const Header& header,
                                 WriterOptions options)
    : m_path(path), m_options(options) {
  if (path.has_parent_path()) std::filesystem::create_directories(path.parent_path());
  m_file = std::fopen(path.string().c_str(), "wb");
  if (m_file == nullptr) throw std::runtime_error("cannot create recording " + path.string());
  const std::vector<std::uint8_t> head = encode_header(header);
  if (std::fwrite(head.data(), 1, head.size(), m_file) != head.size() || std::fflush(m_file) != 0) {
    std::fclose(m_file);
    m_file = nullptr;
    throw std::runtime_error("cannot write recording " + path.string());
  }
  m_stats.bytes = head.size();
  m_thread = std::thread([this] { run(); });
}

RecordingWriter::~RecordingWriter() {
  try {
    abandon();
  } catch (...) {  // NOLINT(bugprone-empty-catch): a destructor must not throw
  }
}

void RecordingWriter::record_inputs(std::uint64_t step, std::span<const ToolState> tools) {
  std::lock_guard lock(m_mutex);
  put_inputs(m_pending, step, tools);
  ++m_stats.steps;
  seal_if_full();
}

// A chunk never grows past chunk_bytes by much (one record): a full payload is sealed here, at a
// record boundary, and the writer thread writes each sealed payload as its own chunk.
void RecordingWriter::seal_if_full() {
  if (m_pending.size() < m_options.chunk_bytes) return;
  m_ready.push_back(std::move(m_pending));
  m_pending.clear();
  m_wake.notify_one();
}

void RecordingWriter::record_hash(std::uint64_t step, std::uint64_t hash) {
  std::lock_guard lock(m_mutex);
  put_hash(m_pending, step, hash);
  seal_if_full();
}

void RecordingWriter::record_snapshot(std::uint64_t steps, std::span<const std::uint8_t> snapshot) {
  if (snapshot_record_bytes(snapshot.size()) > kMaxChunkPayload) {
    record_event(steps,
                 "snapshot left out: " + std::to_string(snapshot.size()) + " bytes exceed a chunk");
    return;
  }
  std::lock_guard lock(m_mutex);
  // A chunk never outgrows kMaxChunkPayload: what is pending goes first.
  if (m_pending.size() + snapshot_record_bytes(snapshot.size()) > kMaxChunkPayload) {
    m_ready.push_back(std::move(m_pending));
    m_pending.clear();
  }
  put_snapshot(m_pending, steps, snapshot);
  ++m_stats.snapshots;
  seal_if_full();
}

void RecordingWriter::record_event(std::uint64_t step, const std::string& text) {
  std::lock_guard lock(m_mutex);
  put_event(m_pending, step, text);
  seal_if_full();
}

void RecordingWriter::write_chunk(std::vector<std::uint8_t>& payload) {
  if (payload.empty()) return;
  const std::vector<std::uint8_t> chunk = encode_chunk(payload);
  payload.clear();
  const bool ok = std::fwrite(chunk.data(), 1, chunk.size(), m_file) == chunk.size() &&
                  std::fflush(m_file) == 0;
  std::lock_guard lock(m_mutex);
  if (!ok && m_error.empty()) m_error = "cannot write recording " + m_path.string();
  ++m_stats.chunks;
  m_stats.bytes += chunk.size();
}

void RecordingWriter::run() {
  std::vector<std::uint8_t> payload;
  std::unique_lock lock(m_mutex);
  while (!m_stop) {
    const bool sealed = m_wake.wait_for(lock, m_options.flush_interval,
                                        [this] { return m_stop || !m_ready.empty(); });
    if (m_stop) break;  // stop() writes the rest itself, in order, with the end record
    if (sealed) {
      payload = std::move(m_ready.front());
      m_ready.pop_front();
    } else if (m_ready.empty()) {  // flush_interval passed: write what is pending
      payload.swap(m_pending);
    }
    lock.unlock();
    write_chunk(payload);
    lock.lock();
  }
}

void RecordingWriter::stop(bool with_end, std::uint64_t steps) {
  if (m_closed) return;
  m_closed = true;
  {
    std::lock_guard lock(m_mutex);
    m_stop = true;
  }
  m_wake.notify_one();
  if (m_thread.joinable()) m_thread.join();
  std::deque<std::vector<std::uint8_t>> ready;
  std::vector<std::uint8_t> payload;
  {
    std::lock_guard lock(m_mutex);
    ready.swap(m_ready);
    payload.swap(m_pending);
  }
  for (std::vector<std::uint8_t>& sealed : ready) write_chunk(sealed);
  if (with_end) put_end(payload, steps);
  write_chunk(payload);
  std::fclose(m_file);
  m_file = nullptr;
}

void RecordingWriter::close(std::uint64_t steps) {
  stop(true, steps);
  std::lock_guard lock(m_mutex);
  if (!m_error.empty()) throw std::runtime_error(m_error);
}

void RecordingWriter::abandon() { stop(false, 0); }

WriterStats RecordingWriter::stats() const {
  std::lock_guard lock(m_mutex);
  return m_stats;
}

}  // namespace serosa::recording
