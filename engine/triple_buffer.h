// TripleBuffer: single producer, single consumer, wait-free hand-off of the latest value. The
// solver publishes a render Frame (at most at the window's frame-rate cap); the renderer takes the
// newest one whenever it draws.
// Neither side ever waits for the other; frames the consumer did not take are overwritten.
// T may own heap memory (vectors): the three slots are reused, so once they have grown to size,
// publishing allocates nothing.
#pragma once

#include <atomic>
#include <cstdint>
#include <utility>

namespace serosa {

template <class T>
class TripleBuffer {
 public:
  TripleBuffer() = default;
  TripleBuffer(const TripleBuffer&) = delete;
  TripleBuffer& operator=(const TripleBuffer&) = delete;

  /// Producer: the slot to fill. Valid until the next publish().
  T& back() noexcept { return m_slots[m_back]; }

  /// Producer: makes back() the newest value and hands the producer a free slot.
  void publish() noexcept {
    const std::uint8_t prev =
        m_middle.exchange(static_cast<std::uint8_t>(m_back | kFresh), std::memory_order_acq_rel);
    m_back = prev & kIndex;
  }

  /// Producer convenience: copies value into the back slot and publishes it.
  void publish(const T& value) {
    back() = value;
    publish();
  }

  /// Consumer: if a newer value was published since the last take, swaps it in and returns true.
  /// front() then refers to it. Never blocks.
  bool take() noexcept {
    if (!(m_middle.load(std::memory_order_relaxed) & kFresh)) return false;
    const std::uint8_t prev = m_middle.exchange(m_front, std::memory_order_acq_rel);
    m_front = prev & kIndex;
    return true;
  }

  /// Consumer: the value last taken (default-constructed T before the first take).
  const T& front() const noexcept { return m_slots[m_front]; }

 private:
  static constexpr std::uint8_t kIndex = 0x3;
  static constexpr std::uint8_t kFresh = 0x4;

  T m_slots[3]{};
  std::uint8_t m_back = 0;                // producer-owned slot index
  std::atomic<std::uint8_t> m_middle{1};  // shared: slot index | kFresh
  std::uint8_t m_front = 2;               // consumer-owned slot index
};

}  // namespace serosa
