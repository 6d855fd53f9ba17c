// vgroove support: run independent work items on several threads.
//
// Items are handed out in chunks from an atomic counter; each writes only its own result slot,
// so the results do not depend on the thread count or on which thread ran what. That also makes
// the loop robust: under an address-space limit it starts no more threads than fit in a quarter
// of it (threads_that_fit), and when the system refuses a thread (a process limit), the items
// run on the threads that did start (at least the caller's); an exception thrown by an
// item (std::bad_alloc) stops the other workers and is rethrown to the caller after all have
// joined, never escaping a worker thread.
//
// Cancellation: long work polls one flag, a `const std::atomic<bool>*` (null: never cancelled),
// set from the SIGINT handler. Every loop that can run for more than a fraction of a second polls
// it (support::cancelled) and stops early; its caller then reports the run as interrupted.
#pragma once

#include <sys/resource.h>

#include <algorithm>
#include <atomic>
#include <climits>
#include <cstddef>
#include <exception>
#include <functional>
#include <mutex>
#include <system_error>
#include <thread>
#include <vector>

namespace vgroove::support {

// The cancellation flag every long loop polls (null: never set).
using CancelFlag = const std::atomic<bool>*;
inline bool cancelled(CancelFlag c) { return c && c->load(std::memory_order_relaxed); }

// Called now and then from one of the workers with the number of items done so far.
using ProgressFn = std::function<void(std::size_t done, std::size_t total)>;

// Threads to use for `requested` (0 = all cores).
inline int resolve_threads(int requested) {
  if (requested > 0) return requested;
  return std::max(1u, std::thread::hardware_concurrency());
}

// The most threads whose stacks take at most a quarter of the address space this process may
// use (ulimit -v): threads that start but leave no room for the work's memory would turn a
// thread limit into an allocation failure. No limit: any number.
inline int threads_that_fit() {
  static const int most = [] {
    struct rlimit as {
    }, stack{};
    if (::getrlimit(RLIMIT_AS, &as) != 0 || as.rlim_cur == RLIM_INFINITY) return INT_MAX;
    double stack_bytes = 8.0 * (1 << 20);  // glibc's default when the stack limit is unlimited
    if (::getrlimit(RLIMIT_STACK, &stack) == 0 && stack.rlim_cur != RLIM_INFINITY && stack.rlim_cur > 0)
      stack_bytes = static_cast<double>(stack.rlim_cur);
    return static_cast<int>(std::clamp(static_cast<double>(as.rlim_cur) / 4.0 / stack_bytes, 1.0, double{INT_MAX}));
  }();
  return most;
}

// Runs fn(i) for i in [0, n). When *cancel becomes true, workers stop at their next chunk and
// parallel_for returns false (some items not run); true when all ran. An exception from fn is
// rethrown here (the first one; the other workers stop at their next chunk).
template <class Fn>
bool parallel_for(std::size_t n, int threads, Fn&& fn, const ProgressFn& progress = {}, CancelFlag cancel = nullptr,
                  std::size_t chunk = 16) {
  std::atomic<std::size_t> next{0}, done{0};
  std::atomic<bool> failed{false};
  std::exception_ptr error;
  std::mutex error_mu;
  auto worker = [&](bool reports) {
    try {
      for (;;) {
        if (cancelled(cancel) || failed.load(std::memory_order_relaxed)) return;
        const std::size_t begin = next.fetch_add(chunk);
        if (begin >= n) return;
        const std::size_t end = std::min(n, begin + chunk);
        for (std::size_t i = begin; i < end; ++i) fn(i);
        const std::size_t d = done.fetch_add(end - begin) + (end - begin);
        if (reports && progress) progress(d, n);
      }
    } catch (...) {
      const std::lock_guard<std::mutex> lock(error_mu);
      if (!error) error = std::current_exception();
      failed.store(true);
    }
  };
  const int t = std::max(1, std::min({threads, static_cast<int>((n + chunk - 1) / chunk), threads_that_fit()}));
  std::vector<std::thread> pool;
  try {
    pool.reserve(static_cast<std::size_t>(t - 1));
    for (int k = 1; k < t; ++k) pool.emplace_back(worker, false);
  } catch (const std::system_error&) {
    // No more threads (EAGAIN): the ones started share the work.
  } catch (const std::bad_alloc&) {
  }
  worker(true);
  for (auto& th : pool) th.join();
  if (error) std::rethrow_exception(error);
  const bool complete = done.load() == n;
  if (progress && complete) progress(n, n);
  return complete;
}

}  // namespace vgroove::support
