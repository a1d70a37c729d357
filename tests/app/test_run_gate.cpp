// The batch's run gate (batch/run_gate.h): a paced run never overlaps another run, ordinary runs
// overlap each other, and a paced run that waits is not overtaken by runs that start after it.
#include <gtest/gtest.h>

#include <atomic>
#include <chrono>
#include <random>
#include <thread>
#include <vector>

#include "batch/run_gate.h"

namespace serosa::batch {
namespace {

using namespace std::chrono_literals;

// Four workers take 300 random runs each (one in five paced) through one gate; inside, each
// checks what runs beside it.
TEST(RunGate, APacedRunNeverOverlapsAnotherAndOrdinaryRunsOverlap) {
  RunGate gate;
  std::atomic<int> shared{0}, alone{0}, violations{0}, max_shared{0};
  auto worker = [&](unsigned seed) {
    std::mt19937 rng(seed);
    for (int k = 0; k < 300; ++k) {
      const bool paced = rng() % 5 == 0;
      gate.enter(paced);
      if (paced) {
        if (alone.fetch_add(1) != 0 || shared.load() != 0) ++violations;
      } else {
        const int now = shared.fetch_add(1) + 1;
        if (alone.load() != 0) ++violations;
        int m = max_shared.load();
        while (now > m && !max_shared.compare_exchange_weak(m, now)) {
        }
      }
      std::this_thread::sleep_for(std::chrono::microseconds(rng() % 200));
      (paced ? alone : shared).fetch_sub(1);
      gate.leave(paced);
    }
  };
  std::vector<std::thread> threads;
  for (unsigned t = 0; t < 4; ++t) threads.emplace_back(worker, 17u + t);
  for (std::thread& t : threads) t.join();
  EXPECT_EQ(violations.load(), 0);
  EXPECT_GE(max_shared.load(), 2) << "ordinary runs should have run side by side";
}

TEST(RunGate, AWaitingPacedRunGoesBeforeRunsThatComeAfterIt) {
  RunGate gate;
  std::atomic<int> order{0}, paced_at{-1}, later_at{-1};
  gate.enter(false);  // a run in progress
  std::thread paced([&] {
    gate.enter(true);
    paced_at = order++;
    gate.leave(true);
  });
  std::this_thread::sleep_for(50ms);  // the paced run is waiting
  std::thread later([&] {
    gate.enter(false);
    later_at = order++;
    gate.leave(false);
  });
  std::this_thread::sleep_for(50ms);
  EXPECT_EQ(paced_at.load(), -1) << "the paced run started beside a run in progress";
  EXPECT_EQ(later_at.load(), -1) << "a run started while a paced run waited";
  gate.leave(false);
  paced.join();
  later.join();
  EXPECT_EQ(paced_at.load(), 0);
  EXPECT_EQ(later_at.load(), 1);
}

}  // namespace
}  // namespace serosa::batch
