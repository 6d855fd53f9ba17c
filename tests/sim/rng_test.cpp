// Tests of sim/rng.h: streams keyed by (seed, a, b), reproducible and distinct; uniform() in [0, 1).
#include "vgroove/sim/rng.h"

#include "vgroove/sim/microsurface.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <vector>

namespace vgroove::sim {
namespace {

std::vector<std::uint64_t> draws(Rng rng, int n) {
  std::vector<std::uint64_t> v;
  for (int j = 0; j < n; ++j) v.push_back(rng.next_u64());
  return v;
}

TEST(Rng, SameKeyGivesTheSameStream) { EXPECT_EQ(draws(Rng(2018, 5, 1), 1000), draws(Rng(2018, 5, 1), 1000)); }

TEST(Rng, EachKeyComponentChangesTheStream) {
  const auto base = draws(Rng(2018, 5, 1), 64);
  EXPECT_NE(draws(Rng(2018, 5, 0), 64), base) << "b";
  EXPECT_NE(draws(Rng(2018, 6, 1), 64), base) << "a";
  EXPECT_NE(draws(Rng(2019, 5, 1), 64), base) << "seed";
  // Swapping a and b is a different work item, so a different stream.
  EXPECT_NE(draws(Rng(2018, 1, 5), 64), base) << "a <-> b";
}

TEST(Rng, NeighbouringStreamsShareNoDraws) {
  // The facets of one case use (seed, case, 0) and (seed, case, 1): no value may repeat between
  // them (64-bit values: a repeat among 2 x 10^4 draws would have probability ~ 1e-11).
  const auto l = draws(Rng(1, 0, 0), 10000), r = draws(Rng(1, 0, 1), 10000);
  std::vector<std::uint64_t> all(l);
  all.insert(all.end(), r.begin(), r.end());
  std::sort(all.begin(), all.end());
  EXPECT_EQ(std::adjacent_find(all.begin(), all.end()), all.end());
}

TEST(Rng, UniformIsInTheUnitIntervalWithMeanOneHalf) {
  // The mean of N uniform draws has standard deviation sqrt(1/12) / sqrt(N).
  constexpr int n = 1'000'000;
  Rng rng(42, 0, 0);
  double sum = 0.0, lo = 1.0, hi = 0.0;
  for (int j = 0; j < n; ++j) {
    const double u = rng.uniform();
    ASSERT_GE(u, 0.0) << "draw " << j;
    ASSERT_LT(u, 1.0) << "draw " << j;
    sum += u;
    lo = std::min(lo, u);
    hi = std::max(hi, u);
  }
  const double sigma = std::sqrt(1.0 / 12.0 / n);
  EXPECT_NEAR(sum / n, 0.5, 5 * sigma);
  // The extremes of 10^6 draws lie within ~1e-5 of the ends (probability of more: e^-10).
  EXPECT_LT(lo, 1e-5);
  EXPECT_GT(hi, 1.0 - 1e-5);
}

// The block draws are the stream's own: next_u64s(n) gives the next n values of next_u64() and
// leaves the stream where n calls would (blocks of every length up to past a vector's width,
// then single draws again).
TEST(Rng, BlockDrawsAreTheSequentialDraws) {
  Rng seq(2018, 3, 7), blk(2018, 3, 7);
  std::uint64_t buf[600];
  for (int n : {0, 1, 2, 3, 4, 5, 7, 8, 255, 256, 512, 513}) {
    blk.next_u64s(buf, n);
    for (int q = 0; q < n; ++q) ASSERT_EQ(buf[q], seq.next_u64()) << "block of " << n << ", value " << q;
    ASSERT_EQ(blk.next_u64(), seq.next_u64()) << "the draw after a block of " << n;
  }
}

// uniform_open_of converts without an integer-to-double instruction: it must be uniform_open bit
// for bit, at the ends (v = 0, v = 2^53 - 1, where v + 1/2 rounds to 2^53: without the clamp to
// the double below 1 the draw would be 1), on both sides of v's top bit (2^52) and at random.
TEST(Rng, BlockUniformsAreUniformOpenBitForBit) {
  std::vector<std::uint64_t> bits = {0,
                                     ~0ULL,
                                     1ULL << 63,
                                     (1ULL << 63) - 1,
                                     (1ULL << 63) | (1ULL << 11),
                                     ((1ULL << 52) - 1) << 11,
                                     (1ULL << 52) << 11,
                                     2047,
                                     2048};
  Rng rng(5, 0, 0);
  for (int j = 0; j < 100000; ++j) bits.push_back(rng.next_u64());
  std::vector<double> u(bits.size());
  uniform_open_of(bits.data(), u.data(), static_cast<int>(bits.size()));
  for (std::size_t q = 0; q < bits.size(); ++q) {
    const double want = std::min(kBelowOne, (static_cast<double>(bits[q] >> 11) + 0.5) * 0x1.0p-53);
    ASSERT_EQ(u[q], want) << "bits " << bits[q];
    ASSERT_GT(u[q], 0.0);
    ASSERT_LT(u[q], 1.0);
  }
}

}  // namespace
}  // namespace vgroove::sim
