// vgroove sim: deterministic random streams, one per work item.
//
// A stream is keyed by (seed, a, b) — for example (suite seed, case index, facet) — so the numbers
// a work item sees never depend on which thread runs it or in which order.
#pragma once

#include <cstdint>

namespace vgroove::sim {

// SplitMix64 (Steele, Lea, Flood 2014): a 64-bit counter through a bijective mixer.
inline std::uint64_t splitmix64(std::uint64_t x) {
  x += 0x9e3779b97f4a7c15ULL;
  x = (x ^ (x >> 30)) * 0xbf58476d1ce4e5b9ULL;
  x = (x ^ (x >> 27)) * 0x94d049bb133111ebULL;
  return x ^ (x >> 31);
}

class Rng {
 public:
  Rng(std::uint64_t seed, std::uint64_t a, std::uint64_t b)
      : state_(splitmix64(splitmix64(splitmix64(seed) ^ a) ^ (b * 0xd1b54a32d192ed03ULL))) {}
  std::uint64_t next_u64() {
    const std::uint64_t s = state_;
    state_ += kStep;
    return splitmix64(s);
  }
  // Uniform in [0, 1) with 53 random bits.
  double uniform() { return static_cast<double>(next_u64() >> 11) * 0x1.0p-53; }
  // The next n values of next_u64(), in order. The state is a counter, so value q is
  // splitmix64(state + q step): a loop without a carried dependence, which vectorizes.
  void next_u64s(std::uint64_t* out, int n) {
    const std::uint64_t s0 = state_;
    for (int q = 0; q < n; ++q) out[q] = splitmix64(s0 + static_cast<std::uint64_t>(q) * kStep);
    state_ = s0 + static_cast<std::uint64_t>(n) * kStep;
  }

 private:
  static constexpr std::uint64_t kStep = 0x9e3779b97f4a7c15ULL;  // splitmix64's own increment
  std::uint64_t state_;
};

// A seed derived from (seed, stream, key): the first value of that stream, for keying a second
// level of streams (a field's, a beam's) from a suite's seed.
inline std::uint64_t derived_seed(std::uint64_t seed, std::uint64_t stream, std::uint64_t key) {
  return Rng(seed, stream, key).next_u64();
}

}  // namespace vgroove::sim
