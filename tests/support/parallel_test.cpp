// Tests of support/parallel.h: every item once, results independent of the thread count,
// exceptions brought back to the caller, cancellation.
#include "vgroove/support/parallel.h"

#include <gtest/gtest.h>

#include <atomic>
#include <new>
#include <stdexcept>
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
// after every worker has stopped, instead of terminating the process.
TEST(ParallelFor, AnExceptionInAWorkerReachesTheCaller) {
  for (int threads : {1, 4}) {
    std::atomic<int> ran{0};
    EXPECT_THROW(parallel_for(
                     10000, threads,
                     [&](std::size_t i) {
                       ++ran;
                       if (i == 5000) throw std::bad_alloc();
                     },
                     {}, nullptr, 1),
                 std::bad_alloc);
    EXPECT_LT(ran.load(), 10000) << "the other workers stop early";
  }
  EXPECT_THROW(parallel_for(3, 2, [](std::size_t) { throw std::runtime_error("x"); }), std::runtime_error);
}

TEST(ParallelFor, CancellationStopsTheWorkers) {
  std::atomic<bool> cancel{false};
  std::atomic<int> ran{0};
  const bool complete = parallel_for(
      100000, 2,
      [&](std::size_t i) {
        ++ran;
        if (i == 10) cancel.store(true);
      },
      {}, &cancel, 1);
  EXPECT_FALSE(complete);
  EXPECT_LT(ran.load(), 100000);
  EXPECT_TRUE(cancelled(&cancel));
  EXPECT_FALSE(cancelled(nullptr));
}

}  // namespace
}  // namespace vgroove::support
