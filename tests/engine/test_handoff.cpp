// Hand-off primitives under concurrent use: readers must never see a torn value and the consumer
// must only ever see values in publication order. Run under ThreadSanitizer in the tsan preset.
#include <gtest/gtest.h>

#include <array>
#include <atomic>
#include <cstdint>
#include <thread>
#include <vector>

#include "engine/seqlock.h"
#include "engine/tool_state.h"
#include "engine/triple_buffer.h"

namespace serosa {
namespace {

// A value whose fields must all agree: a torn read shows up as a mismatch.
struct Stamped {
  std::uint64_t seq = 0;
  std::array<std::uint64_t, 7> copies{};
};

TEST(Seqlock, SingleThreadRoundTrip) {
  Seqlock<ToolState> lock;
  ToolState s;
  s.tick = 42;
  s.tip_m = {0.1, -0.2, 0.3};
  s.jaw_rad = 0.5;
  lock.store(s);
  const ToolState r = lock.load();
  EXPECT_EQ(r.tick, 42u);
  EXPECT_EQ(r.tip_m[1], -0.2);
  EXPECT_EQ(r.jaw_rad, 0.5);
  EXPECT_EQ(lock.version(), 1u);
}

TEST(Seqlock, ReadersNeverSeeTornValuesAndNeverGoBack) {
  Seqlock<Stamped> lock;
  constexpr std::uint64_t kWrites = 200000;
  std::atomic<bool> done{false};
  std::atomic<std::uint64_t> bad{0};
  std::vector<std::thread> readers;
  for (int r = 0; r < 2; ++r) {
    readers.emplace_back([&] {
      std::uint64_t last = 0;
      while (!done.load(std::memory_order_acquire)) {
        const Stamped v = lock.load();
        for (std::uint64_t c : v.copies)
          if (c != v.seq) bad.fetch_add(1);
        if (v.seq < last) bad.fetch_add(1);
        last = v.seq;
      }
    });
  }
  for (std::uint64_t i = 1; i <= kWrites; ++i) {
    Stamped v;
    v.seq = i;
    v.copies.fill(i);
    lock.store(v);
  }
  done.store(true, std::memory_order_release);
  for (auto& t : readers) t.join();
  EXPECT_EQ(bad.load(), 0u);
  EXPECT_EQ(lock.load().seq, kWrites);
  EXPECT_EQ(lock.version(), kWrites);
}

TEST(TripleBuffer, TakeReturnsOnlyNewValues) {
  TripleBuffer<int> tb;
  EXPECT_FALSE(tb.take());
  tb.publish(1);
  tb.publish(2);
  ASSERT_TRUE(tb.take());
  EXPECT_EQ(tb.front(), 2);  // the newest wins; 1 was dropped
  EXPECT_FALSE(tb.take());
  EXPECT_EQ(tb.front(), 2);
  tb.publish(3);
  ASSERT_TRUE(tb.take());
  EXPECT_EQ(tb.front(), 3);
}

TEST(TripleBuffer, ConsumerSeesIncreasingWholeFrames) {
  // Frames own heap memory, as render frames do: every element must match the frame number.
  struct Frame {
    std::uint64_t id = 0;
    std::vector<std::uint64_t> data;
  };
  TripleBuffer<Frame> tb;
  constexpr std::uint64_t kFrames = 100000;
  std::atomic<bool> done{false};
  std::uint64_t bad = 0, taken = 0, last = 0;
  std::thread consumer([&] {
    while (true) {
      const bool finished = done.load(std::memory_order_acquire);
      if (tb.take()) {
        const Frame& f = tb.front();
        ++taken;
        if (f.id <= last) ++bad;
        for (std::uint64_t d : f.data)
          if (d != f.id) ++bad;
        last = f.id;
      } else if (finished) {
        break;
      }
    }
  });
  for (std::uint64_t i = 1; i <= kFrames; ++i) {
    Frame& f = tb.back();
    f.id = i;
    f.data.assign(16, i);
    tb.publish();
  }
  done.store(true, std::memory_order_release);
  consumer.join();
  EXPECT_EQ(bad, 0u);
  EXPECT_GE(taken, 1u);
  EXPECT_EQ(last, kFrames);  // the last frame is never lost
}

}  // namespace
}  // namespace serosa
