// Tests of sim/exit_bins.h: the arctangent guess's error bound, and the bins found from it (by the
// edge tests, and from the guess alone away from the edges) against floor(atan2 / width).
#include "vgroove/sim/exit_bins.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <limits>
#include <numbers>
#include <random>

namespace vgroove::sim {
namespace {

constexpr double kPi = std::numbers::pi;

// The guess is within kAtan2GuessError (1e-7 rad) of std::atan2: a sweep of 2 x 10^6 angles over
// the circle (octant boundaries included) and random points, some with one coordinate 1e-9 or
// 1e-12 of the other. Measured 3.8e-8. (The cubic it replaced was off by 2e-4 near pi/4, more
// than a bin 1.6e-4 wide: this test fails with it.)
TEST(ExitBins, Atan2GuessIsWithinItsBound) {
  double worst = 0.0;
  for (int n = 0; n <= 2000000; ++n) {
    const double a = -kPi + 2.0 * kPi * n / 2000000.0;
    const double x = std::cos(a), y = std::sin(a);
    worst = std::max(worst, std::abs(atan2_guess(y, x) - std::atan2(y, x)));
  }
  std::mt19937_64 rng(5);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  for (int n = 0; n < 1000000; ++n) {
    double x = u(rng), y = u(rng);
    if (n % 7 == 0) x *= 1e-9;
    if (n % 11 == 0) y *= 1e-12;
    worst = std::max(worst, std::abs(atan2_guess(y, x) - std::atan2(y, x)));
  }
  EXPECT_LT(worst, kAtan2GuessError);
  EXPECT_GT(worst, 1e-9) << "a polynomial this short cannot be exact: the sweep measured nothing";
  EXPECT_EQ(atan2_guess(0.0, 1.0), 0.0);
  EXPECT_EQ(atan2_guess(1.0, 0.0), 0.5 * kPi);
}

// The bins at the 3D tallies' finest (theta: 10,000 bins over 90 deg, 1.6e-4 rad wide) and a
// coarse phi layout: bin_branchless is floor(atan2 / width) for every direction away from an edge
// (within 1e-12 rad of one, either answer is right), and bin_if_far, where it answers, is
// bin_branchless's bin; it declines only within ~2e-7 rad of an edge (a fraction ~2.5e-3 of
// directions at this width, measured below 1e-2).
TEST(ExitBins, BinsFromTheGuessAreTheEdgeTestsBins) {
  struct Layout {
    double lo, w;
    int n;
  };
  for (const Layout& L : {Layout{0.0, 0.5 * kPi / 10000, 10000}, Layout{-kPi - kPi / 24, 2.0 * kPi / 24, 25}}) {
    const AngleEdges e(L.lo, L.w, L.n);
    std::mt19937_64 rng(11);
    std::uniform_real_distribution<double> u(0.0, 1.0);
    std::int64_t declined = 0, compared = 0;
    for (int n = 0; n < 400000; ++n) {
      // Angles over the layout's range (theta: [0, pi/2]; phi: (-pi, pi]).
      const double a = L.lo > -1.0 ? 0.5 * kPi * u(rng) : kPi * (2.0 * u(rng) - 1.0);
      const double r = 0.1 + u(rng), x = r * std::cos(a), y = r * std::sin(a);
      const double g = atan2_guess(y, x);
      const double exact = std::clamp(std::floor((std::atan2(y, x) - L.lo) / L.w), 0.0, L.n - 1.0);
      const double edge_dist = std::abs(std::remainder(std::atan2(y, x) - L.lo, L.w));
      const double branchless = e.bin_branchless(x, y, g);
      if (edge_dist > 1e-12) {
        ++compared;
        ASSERT_EQ(branchless, exact) << "angle " << a;
        ASSERT_EQ(e.bin(x, y, g), static_cast<int>(exact)) << "angle " << a;
      }
      const double far = e.bin_if_far(g);
      if (far < 0.0) {
        ++declined;
      } else {
        ASSERT_EQ(far, branchless) << "angle " << a;
      }
    }
    EXPECT_GT(compared, 399000);
    EXPECT_LT(declined, 4000) << "n " << L.n;
    // A NaN guess is declined, and the edge tests then answer a bin in range (no cast of a NaN).
    const double nan = std::numeric_limits<double>::quiet_NaN();
    EXPECT_EQ(e.bin_if_far(nan), -1.0);
    const double b = e.bin_branchless(1.0, 0.0, nan);
    EXPECT_GE(b, 0.0);
    EXPECT_LE(b, L.n - 1.0);
  }
}

}  // namespace
}  // namespace vgroove::sim
