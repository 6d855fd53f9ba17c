// Tests of the polynomial exp and log (analytic/detail/exp_log_batch.h), four lanes at a time, against
// long double: the batched BRDF pass's Beckmann terms and the lobe's nodes rest on them.
#include "vgroove/analytic/detail/exp_log_batch.h"

#include "tests/ulps.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <random>
#include <vector>

namespace va = vgroove::analytic;

using vgroove::test_ulps::ulps;

namespace {

enum class Fn { exp, expm1, log };

// The function over the values, four lanes at a time (no vector passes a function boundary: the
// tests are compiled for any x86-64).
std::vector<double> by_lanes(const std::vector<double>& x, Fn fn) {
  std::vector<double> y(x.size());
  for (std::size_t n = 0; n + 4 <= x.size(); n += 4) {
    const va::batch::V4 v{x[n], x[n + 1], x[n + 2], x[n + 3]};
    const va::batch::V4 r = fn == Fn::log     ? va::batch::log_batch(v)
                            : fn == Fn::expm1 ? va::batch::expm1_batch(v)
                                              : va::batch::exp_batch(v);
    for (int l = 0; l < 4; ++l) y[n + l] = r[l];
  }
  return y;
}

// The largest distance in ulp of the function over the values (padded to whole lanes with
// `pad`) from its long double value.
double worst_ulps(std::vector<double> x, Fn fn, double pad) {
  while (x.size() % 4 != 0) x.push_back(pad);
  const std::vector<double> y = by_lanes(x, fn);
  double worst = 0.0;
  for (std::size_t n = 0; n < x.size(); ++n) {
    const long double v = x[n];
    const long double exact = fn == Fn::log ? std::log(v) : (fn == Fn::expm1 ? std::expm1(v) : std::exp(v));
    worst = std::max(worst, ulps(y[n], exact));
  }
  return worst;
}

}  // namespace

// Over the range [-708, 709]: uniformly, near 0, both sides of the reduction points
// (k + 1/2) ln 2, and the ends. Measured worst: 0.97 ulp. Tolerance 2 ulp.
TEST(ExpLogBatch, ExpWithinTwoUlpOverItsRange) {
  std::mt19937_64 g(11);
  std::uniform_real_distribution<double> U(-708.0, 709.0), S(-1.0, 1.0);
  std::vector<double> z;
  for (int n = 0; n < 200000; ++n) z.push_back(U(g));
  for (int n = 0; n < 100000; ++n) z.push_back(S(g) * std::pow(10.0, -16.0 * std::abs(S(g))));
  for (int k = -1000; k <= 1000; ++k) {
    const double mid = (k + 0.5) * 0.69314718055994530942;
    for (double d : {-1e-12, 0.0, 1e-12}) z.push_back(mid + d);
  }
  for (double e : {-708.0, 709.0, 0.0, -0.0}) z.push_back(e);
  z.erase(std::remove_if(z.begin(), z.end(), [](double v) { return v < -708.0 || v > 709.0; }), z.end());
  EXPECT_LE(worst_ulps(z, Fn::exp, 0.0), 2.0);
}

// e^z - 1 over [-708, 709]: uniformly, near 0 down to 1e-300 (where only the series keeps the
// result's digits), both sides of +-ln 2 / 2 (where k leaves 0). Measured worst: 1.91 ulp.
// Tolerance 2 ulp.
TEST(ExpLogBatch, Expm1WithinTwoUlpOverItsRange) {
  std::mt19937_64 g(17);
  std::uniform_real_distribution<double> U(-708.0, 709.0), S(-1.0, 1.0);
  std::vector<double> z;
  for (int n = 0; n < 100000; ++n) z.push_back(U(g));
  for (int n = 0; n < 100000; ++n) z.push_back(S(g) * std::pow(10.0, -300.0 * std::abs(S(g))));
  for (int n = 0; n < 100000; ++n) z.push_back(2.0 * S(g));
  for (double c : {-0.34657359027997264, 0.34657359027997264})
    for (double d = 1e-16; d < 1e-3; d *= 3.0)
      for (double v : {c - d, c, c + d}) z.push_back(v);
  z.erase(std::remove_if(z.begin(), z.end(), [](double v) { return v < -708.0 || v > 709.0 || v == 0.0; }), z.end());
  EXPECT_LE(worst_ulps(z, Fn::expm1, 1.0), 2.0);
}

// Over the positive normal numbers: uniformly in the exponent, near 1 (where log is small and its
// relative accuracy matters), the mantissa uniformly, and both sides of the split at sqrt(2) and of
// every power of two. Measured worst: 1.93 ulp. Tolerance 2 ulp.
TEST(ExpLogBatch, LogWithinTwoUlpOfItsValue) {
  std::mt19937_64 g(13);
  std::uniform_real_distribution<double> U(-1022.0, 1023.0), S(-1.0, 1.0), M(1.0, 2.0);
  std::vector<double> x;
  for (int n = 0; n < 200000; ++n) x.push_back(std::exp2(U(g)));
  for (int n = 0; n < 100000; ++n) x.push_back(1.0 + S(g) * std::pow(10.0, -16.0 * std::abs(S(g))));
  for (int n = 0; n < 100000; ++n) x.push_back(M(g));
  for (int e = -1022; e <= 1023; ++e) {
    const double p = std::ldexp(1.0, e);
    for (double v :
         {p, std::nextafter(p, 0.0), p * 1.41421356237309504880, std::nextafter(p * 1.41421356237309504880, 0.0)})
      x.push_back(v);
  }
  x.erase(
      std::remove_if(x.begin(), x.end(),
                     [](double v) { return !(v >= std::numeric_limits<double>::min()) || v == 1.0 || std::isinf(v); }),
      x.end());
  EXPECT_LE(worst_ulps(x, Fn::log, 2.0), 2.0);
  EXPECT_EQ(by_lanes({1.0, 1.0, 1.0, 1.0}, Fn::log)[2], 0.0);
}
