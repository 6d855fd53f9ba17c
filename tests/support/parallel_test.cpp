// Tests of support/parallel.h: every item once, results independent of the thread count,
// exceptions brought back to the caller, cancellation.
#include "vgroove/support/parallel.h"

#include <gtest/gtest.h>

#include <atomic>
#include <chrono>
#include <new>
#include <stdexcept>
#include <thread>
#include <vector>

namespace vgroove::support {
namespace {

TEST(ParallelFor, RunsEveryItemOnce) {
  for (int threads : {1, 2, 7}) {
    std::vector<int> hits(1000, 0);
    EXPECT_TRUE(parallel_for(hits.size(), threads, [&](std::size_t i) { ++hits[i]; }));
    for (int h : hits) EXPECT_EQ(h, 1) << "threads " << threads;
  }
}

// An exception in a worker (std::bad_alloc when a case does not fit) comes back to the caller
// after every worker has stopped, instead of terminating the process. Items past the throwing one
// wait for the throw and then take 100 us each, so the other workers would need about 0.2 s to run
// them all: they stop first unless the thrower is held off the CPU that long (the items alone take
// microseconds, and without the wait another worker could finish them all before the throw is
// recorded).
TEST(ParallelFor, AnExceptionInAWorkerReachesTheCaller) {
  for (int threads : {1, 4}) {
    std::atomic<int> ran{0};
    std::atomic<bool> thrown{false};
    EXPECT_THROW(parallel_for(
                     10000, threads,
                     [&](std::size_t i) {
                       ++ran;
                       if (i == 5000) {
                         thrown.store(true);
                         throw std::bad_alloc();
                       }
                       if (i < 5000) return;
                       while (!thrown.load()) std::this_thread::yield();
                       std::this_thread::sleep_for(std::chrono::microseconds(100));
                     },
                     {}, nullptr, 1),
                 std::bad_alloc);
    if (threads == 1) {
      EXPECT_EQ(ran.load(), 5001) << "one worker stops at the throw";
    } else {
      EXPECT_LT(ran.load(), 10000) << "the other workers stop early";
    }
  }
  EXPECT_THROW(parallel_for(3, 2, [](std::size_t) { throw std::runtime_error("x"); }), std::runtime_error);
}

// Items past the cancelling one wait for the flag, so no worker can run them all before it is set.
TEST(ParallelFor, CancellationStopsTheWorkers) {
  std::atomic<bool> cancel{false};
  std::atomic<int> ran{0};
  const bool complete = parallel_for(
      100000, 2,
      [&](std::size_t i) {
        ++ran;
        if (i == 10) cancel.store(true);
        while (i > 10 && !cancel.load()) std::this_thread::yield();
      },
      {}, &cancel, 1);
  EXPECT_FALSE(complete);
  EXPECT_LT(ran.load(), 100000);
  EXPECT_TRUE(cancelled(&cancel));
  EXPECT_FALSE(cancelled(nullptr));
}

}  // namespace
}  // namespace vgroove::support
