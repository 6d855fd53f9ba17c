// vgroove support: run independent work items on several threads.
//
// Items are handed out in chunks from an atomic counter; each writes only its own result slot,
// so the results do not depend on the thread count or on which thread ran what.
#pragma once

#include <algorithm>
#include <atomic>
#include <cstddef>
#include <functional>
#include <thread>
#include <vector>

namespace vgroove::support {

// Called now and then from one of the workers with the number of items done so far.
using ProgressFn = std::function<void(std::size_t done, std::size_t total)>;

// Threads to use for `requested` (0 = all cores).
inline int resolve_threads(int requested) {
  if (requested > 0) return requested;
  return std::max(1u, std::thread::hardware_concurrency());
}

// Runs fn(i) for i in [0, n). When *cancel becomes true, workers stop at their next chunk and
// parallel_for returns false (some items not run); true when all ran.
template <class Fn>
bool parallel_for(std::size_t n, int threads, Fn&& fn, const ProgressFn& progress = {},
                  const std::atomic<bool>* cancel = nullptr, std::size_t chunk = 16) {
  std::atomic<std::size_t> next{0}, done{0};
  auto worker = [&](bool reports) {
    for (;;) {
      if (cancel && cancel->load(std::memory_order_relaxed)) return;
      const std::size_t begin = next.fetch_add(chunk);
      if (begin >= n) return;
      const std::size_t end = std::min(n, begin + chunk);
      for (std::size_t i = begin; i < end; ++i) fn(i);
      const std::size_t d = done.fetch_add(end - begin) + (end - begin);
      if (reports && progress) progress(d, n);
    }
  };
  const int t = std::max(1, std::min<int>(threads, static_cast<int>((n + chunk - 1) / chunk)));
  std::vector<std::thread> pool;
  for (int k = 1; k < t; ++k) pool.emplace_back(worker, false);
  worker(true);
  for (auto& th : pool) th.join();
  const bool complete = done.load() == n;
  if (progress && complete) progress(n, n);
  return complete;
}

}  // namespace vgroove::support
