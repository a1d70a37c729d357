// Seqlock: one writer publishes a small trivially copyable value; readers never block the writer
// and retry when they raced it. Used for ToolState (haptics -> solver) and HapticModel
// (solver -> haptics): the 1 kHz loop writes without waiting and reads without a lock.
#pragma once

#include <atomic>
#include <cstddef>
#include <cstdint>
#include <cstring>
#include <type_traits>

namespace serosa {

template <class T>
class Seqlock {
  static_assert(std::is_trivially_copyable_v<T>, "Seqlock<T> needs a trivially copyable T");

 public:
  Seqlock() = default;
  explicit Seqlock(const T& initial) { store(initial); }

  /// Single writer. Wait-free: two counter increments and a copy.
  void store(const T& value) noexcept {
    const std::uint64_t s = m_seq.load(std::memory_order_relaxed);
    m_seq.store(s + 1, std::memory_order_relaxed);  // odd: write in progress
    std::atomic_thread_fence(std::memory_order_release);
    copy_in(value);
    m_seq.store(s + 2, std::memory_order_release);  // even: stable
  }

  /// Any number of readers. Lock-free: retries while a write is in progress or raced.
  [[nodiscard]] T load() const noexcept {
    T out;
    while (!try_load(out)) {
    }
    return out;
  }

  /// One attempt; false if a write raced the read (out is then unspecified).
  bool try_load(T& out) const noexcept {
    const std::uint64_t s0 = m_seq.load(std::memory_order_acquire);
    if (s0 & 1u) return false;
    copy_out(out);
    std::atomic_thread_fence(std::memory_order_acquire);
    return m_seq.load(std::memory_order_relaxed) == s0;
  }

  /// Number of completed stores.
  [[nodiscard]] std::uint64_t version() const noexcept {
    return m_seq.load(std::memory_order_acquire) / 2;
  }

 private:
  // The payload is copied word by word through relaxed atomics, so a racing read is not a data
  // race in the C++ memory model (and ThreadSanitizer agrees); torn reads are caught by m_seq.
  static constexpr std::size_t kWords =
      (sizeof(T) + sizeof(std::uint64_t) - 1) / sizeof(std::uint64_t);

  void copy_in(const T& value) noexcept {
    std::uint64_t buf[kWords] = {};
    std::memcpy(buf, &value, sizeof(T));
    for (std::size_t i = 0; i < kWords; ++i) m_data[i].store(buf[i], std::memory_order_relaxed);
  }
  void copy_out(T& out) const noexcept {
    std::uint64_t buf[kWords];
    for (std::size_t i = 0; i < kWords; ++i) buf[i] = m_data[i].load(std::memory_order_relaxed);
    std::memcpy(&out, buf, sizeof(T));
  }

  std::atomic<std::uint64_t> m_seq{0};
  std::atomic<std::uint64_t> m_data[kWords] = {};
};

}  // namespace serosa
