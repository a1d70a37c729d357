// A scriptable in-memory Device for loop tests: fresh samples on demand, plug/unplug, a stall
// hook, and every command recorded into a preallocated buffer (no allocation on the loop thread).
#pragma once

#include <atomic>
#include <chrono>
#include <thread>
#include <vector>

#include "haptics/device.h"

namespace serosa::haptics::testing {

class FakeDevice final : public Device {
 public:
  struct Record {
    double time_s = 0.0;
    DeviceCommand cmd;
  };

  explicit FakeDevice(std::array<Trocar, kHandles> trocars = {}, std::size_t capacity = 4000)
      : m_trocars(trocars) {
    m_records.resize(capacity);
    for (auto& j : m_joints) j.insertion_m = 0.1;
  }

  bool poll(double now_s, DeviceSample& out) noexcept override {
    if (m_first_poll_thread.load() == std::thread::id()) {
      m_first_poll_thread.store(std::this_thread::get_id());
    }
    m_now = now_s;
    const int stall_ms = m_stall_ms.exchange(0);
    if (stall_ms > 0) std::this_thread::sleep_for(std::chrono::milliseconds(stall_ms));
    if (!m_fresh.load() || !m_connected.load()) return false;
    DeviceSample s;
    s.sequence = ++m_seq;
    s.time_s = now_s;
    for (std::size_t h = 0; h < kHandles; ++h) {
      s.joints[h] = m_joints[h];
      s.pose[h] = forward(m_trocars[h], m_joints[h]);
    }
    out = s;
    return true;
  }
  [[nodiscard]] bool connected() const noexcept override { return m_connected.load(); }
  void command(const DeviceCommand& c) noexcept override {
    const std::size_t i = m_count.load(std::memory_order_relaxed);
    if (i < m_records.size()) {
      m_records[i].time_s = m_now;
      m_records[i].cmd = c;
      m_count.store(i + 1, std::memory_order_release);
    }
  }
  [[nodiscard]] const char* name() const noexcept override { return "fake"; }

  // Test controls.
  void set_connected(bool c) { m_connected.store(c); }
  void set_fresh(bool f) { m_fresh.store(f); }
  void stall_next_poll_ms(int ms) { m_stall_ms.store(ms); }
  void set_joints(std::size_t h, const JointState& q) { m_joints[h] = q; }  // tick-driven tests
  [[nodiscard]] std::size_t count() const { return m_count.load(std::memory_order_acquire); }
  [[nodiscard]] const Record& record(std::size_t i) const { return m_records[i]; }
  [[nodiscard]] const Record& last() const { return m_records[count() - 1]; }
  [[nodiscard]] std::thread::id loop_thread() const { return m_first_poll_thread.load(); }

 private:
  std::array<Trocar, kHandles> m_trocars;
  std::array<JointState, kHandles> m_joints{};
  std::atomic<bool> m_connected{true};
  std::atomic<bool> m_fresh{true};
  std::atomic<int> m_stall_ms{0};
  std::atomic<std::thread::id> m_first_poll_thread{};
  std::uint64_t m_seq = 0;
  double m_now = 0.0;
  std::vector<Record> m_records;
  std::atomic<std::size_t> m_count{0};
};

}  // namespace serosa::haptics::testing
