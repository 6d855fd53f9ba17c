// Tests of the chi-square goodness-of-fit test (validation/chi_square.h): the survival function at
// tabulated points, Sidak's correction, the pooling, and its behaviour on draws from a known
// multinomial (passes the right probabilities at the stated rate, rejects wrong ones).
#include "vgroove/validation/chi_square.h"

#include <gtest/gtest.h>
#include <boost/math/special_functions/gamma.hpp>

#include <cmath>
#include <random>
#include <vector>

namespace vgroove::validation {
namespace {

TEST(ChiSquare, SurvivalFunctionAtTabulatedPoints) {
  // Q(1, x) = exp(-x): two degrees of freedom.
  for (double x : {0.1, 1.0, 5.0, 30.0})
    EXPECT_NEAR(chi_square_sf(2.0 * x, 2), std::exp(-x), 1e-14 * std::exp(-x) + 1e-300);
  // The 5 % and 1 % critical values of standard tables.
  EXPECT_NEAR(chi_square_sf(3.841458820694124, 1), 0.05, 1e-12);
  EXPECT_NEAR(chi_square_sf(6.634896601021214, 1), 0.01, 1e-12);
  EXPECT_NEAR(chi_square_sf(18.307038053275146, 10), 0.05, 1e-12);
  EXPECT_NEAR(chi_square_sf(124.34211340400407, 100), 0.05, 1e-11);
  EXPECT_EQ(chi_square_sf(0.0, 5), 1.0);
}

// The library's survival function against Boost.Math's regularized incomplete gamma, an
// independent implementation, from the far left tail to p ~ 1e-30, over 1 to 10^4 degrees of
// freedom (where the series and the continued fraction hand over, x = a + 1, included).
TEST(ChiSquare, SurvivalFunctionAgreesWithBoostMath) {
  for (const int dof : {1, 2, 3, 5, 8, 13, 30, 100, 457, 1000, 10000}) {
    const double a = 0.5 * dof;
    for (const double x : {1e-3 * dof, 0.1 * dof, 0.5 * dof, 2.0 * a + 2.0, 1.0 * dof, 1.5 * dof + 1.0,
                           3.0 * dof + 20.0, 5.0 * dof + 100.0}) {
      const double want = boost::math::gamma_q(a, 0.5 * x);
      if (want < 1e-30) continue;
      EXPECT_NEAR(chi_square_sf(x, dof), want, 1e-12 * want + 1e-15) << "dof " << dof << ", x " << x;
    }
  }
}

TEST(ChiSquare, SidakCorrection) {
  EXPECT_NEAR(sidak_level(0.01, 1), 0.01, 1e-16);
  // 1 - 0.99^(1/100) = 1.00498308e-4 (Python: 1 - 0.99 ** 0.01; the direct form loses ~1e-13 relative).
  EXPECT_NEAR(sidak_level(0.01, 100), 1.0049830824166e-4, 1e-16);
  // The family's level: 1 - (1 - level_1)^tests = level.
  EXPECT_NEAR(1.0 - std::pow(1.0 - sidak_level(0.01, 450), 450), 0.01, 1e-14);
}

// Cells expecting fewer than 5 are pooled (in order of expected count) until a pool expects 5; an
// incomplete last pool joins the next cell. Here: 1 + 1 + 1 + 1 + 1 = 5 is one pooled cell, 2 + 2
// joins the cell expecting 10, and the cell expecting 20 stands alone: 3 cells, dof 2.
TEST(ChiSquare, PoolsCellsThatExpectFewerThanFive) {
  const std::vector<double> expected{1, 1, 1, 1, 1, 2, 2, 10, 20};
  const std::vector<double> observed{0, 2, 1, 1, 1, 3, 1, 9, 21};
  const ChiSquareResult r = chi_square_test(observed, expected, 0.01, 1);
  EXPECT_EQ(r.pooled_in, 7);
  EXPECT_EQ(r.pooled_out, 1);
  EXPECT_EQ(r.dof, 2);
  // (5 - 5)^2/5 + (13 - 14)^2/14 + (21 - 20)^2/20.
  EXPECT_NEAR(r.statistic, 1.0 / 14.0 + 1.0 / 20.0, 1e-15);
  EXPECT_FALSE(r.reject);
}

TEST(ChiSquare, SamplesWhereNoneAreExpectedReject) {
  const ChiSquareResult r = chi_square_test({10, 10, 1}, {10.5, 10.5, 0.0}, 0.01, 1);
  EXPECT_TRUE(r.samples_where_none_expected);
  EXPECT_TRUE(r.reject);
}

// Draws from a known multinomial: the right probabilities are rejected in about `level` of the
// trials (binomial bound), probabilities off by 30 % in one cell (moved to its neighbour; the
// noncentrality ~ 70 at dof 39) nearly always.
TEST(ChiSquare, RejectionRateOnAKnownMultinomial) {
  const int cells = 40, n = 20000, trials = 400;
  std::vector<double> p(cells);
  double total = 0.0;
  for (int c = 0; c < cells; ++c) total += (p[c] = 1.0 + c % 7 + 0.05 * c);
  for (double& v : p) v /= total;
  std::mt19937_64 g(91);
  std::discrete_distribution<int> draw(p.begin(), p.end());
  int rejected_right = 0, rejected_wrong = 0;
  for (int t = 0; t < trials; ++t) {
    std::vector<double> observed(cells, 0.0), expected(cells), wrong(cells);
    for (int s = 0; s < n; ++s) observed[draw(g)] += 1.0;
    for (int c = 0; c < cells; ++c) expected[c] = n * p[c];
    wrong = expected;
    wrong[3] *= 1.3;
    wrong[4] -= 0.3 * expected[3];
    rejected_right += chi_square_test(observed, expected, 0.05, 1).reject;
    rejected_wrong += chi_square_test(observed, wrong, 0.05, 1).reject;
  }
  // 400 trials at 5 %: mean 20, sd 4.4; within 4 sd.
  EXPECT_NEAR(rejected_right, 20.0, 4.0 * std::sqrt(400 * 0.05 * 0.95));
  EXPECT_GT(rejected_wrong, 0.9 * trials);
}

}  // namespace
}  // namespace vgroove::validation
