// The 1 kHz loop allocates nothing once running: global operator new counts allocations made on
// the loop thread while the solver publishes models, the device unplugs and replugs, and NaNs
// arrive.
#include <gtest/gtest.h>

#include <atomic>
#include <chrono>
#include <cstdlib>
#include <limits>
#include <new>
#include <thread>

#include "fake_device.h"
#include "haptics/haptic_loop.h"

namespace {
std::atomic<std::thread::id> g_watched{};
std::atomic<long> g_allocations{0};

void* counted_alloc(std::size_t n) {
  if (std::this_thread::get_id() == g_watched.load(std::memory_order_relaxed)) ++g_allocations;
  if (void* p = std::malloc(n ? n : 1)) return p;
  throw std::bad_alloc();
}
}  // namespace

// Every global new and delete is replaced as a pair over malloc and free. Where GCC inlines the
// replaced delete into a `new T` it no longer sees the pair and warns (-Wmismatched-new-delete,
// seen at -O1 under ThreadSanitizer), though malloc's pointer goes back to free.
#if defined(__GNUC__) && !defined(__clang__)
#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wmismatched-new-delete"
#endif
void* operator new(std::size_t n) { return counted_alloc(n); }
void* operator new[](std::size_t n) { return counted_alloc(n); }
void operator delete(void* p) noexcept { std::free(p); }
void operator delete[](void* p) noexcept { std::free(p); }
void operator delete(void* p, std::size_t) noexcept { std::free(p); }
void operator delete[](void* p, std::size_t) noexcept { std::free(p); }
#if defined(__GNUC__) && !defined(__clang__)
#pragma GCC diagnostic pop
#endif

namespace serosa::haptics {
namespace {

TEST(HapticLoopThread, NoAllocationInsideTheLoop) {
  testing::FakeDevice dev;
  ContactModel m;
  m.step = 1;
  m.tools[0].n_contacts = 1;
  m.tools[0].contacts[0].point_m = {0.0, 0.0, 0.095};
  m.tools[0].contacts[0].normal = {0.0, 0.0, -1.0};
  m.tools[0].contacts[0].stiffness_Npm = 300.0;
  ContactModelChannel ch(m);
  HapticLoopConfig c;
  c.gap_monitor = true;
  HapticLoop loop(dev, ch, c);
  loop.start();
  std::this_thread::sleep_for(std::chrono::milliseconds(50));
  ASSERT_NE(dev.loop_thread(), std::thread::id());
  g_watched.store(dev.loop_thread());
  g_allocations.store(0);
  for (std::uint64_t step = 2; step < 30; ++step) {  // the solver at ~200 Hz
    m.step = step;
    m.cut_events = static_cast<std::uint32_t>(step / 10);
    m.tools[0].contacts[0].stiffness_Npm =
        step == 15 ? std::numeric_limits<double>::quiet_NaN() : 300.0;
    ch.store(m);
    if (step == 20) dev.set_connected(false);
    if (step == 22) dev.set_connected(true);
    std::this_thread::sleep_for(std::chrono::milliseconds(5));
  }
  const long allocations = g_allocations.load();
  g_watched.store(std::thread::id());
  loop.stop();
  EXPECT_EQ(allocations, 0);
  EXPECT_GT(loop.telemetry().models, 10u);
  EXPECT_GT(loop.telemetry().zero_ticks[static_cast<std::size_t>(ZeroReason::kUnplugged)], 0u);
}

}  // namespace
}  // namespace serosa::haptics
