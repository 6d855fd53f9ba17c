// compare_lobes: the shape and joint L1 tests and the albedo threshold every lobe-binning kind
// uses, on hand-made lobes.
#include "vgroove/validation/lobe_comparison.h"

#include <gtest/gtest.h>

#include <cmath>
#include <vector>

namespace vgroove::validation {
namespace {

// Two rows (k = 1, 2) of three bins; 0.9 of the flux leaves.
const std::vector<double> kModel = {0.2, 0.3, 0.1, 0.1, 0.1, 0.1};

TEST(LobeComparison, BinTotalsSumTheRowsPerBin) {
  const std::vector<double> t = bin_totals(kModel, 3);
  ASSERT_EQ(t.size(), 3u);
  EXPECT_DOUBLE_EQ(t[0], 0.3);
  EXPECT_DOUBLE_EQ(t[1], 0.4);
  EXPECT_DOUBLE_EQ(t[2], 0.2);
}

TEST(LobeComparison, AnEqualLobeHoldsWithZeroDistance) {
  const LobeComparison c = compare_lobes(kModel, kModel, 3, 1e6, 1e6, 5.0, 0.0);
  EXPECT_EQ(c.shape.l1, 0.0);
  EXPECT_EQ(c.joint.l1, 0.0);
  EXPECT_GT(c.shape.expected, 0.0);
  EXPECT_TRUE(c.shape.holds());
  EXPECT_TRUE(c.joint.holds());
  ASSERT_EQ(c.sim_shape.size(), 3u);
  EXPECT_NEAR(c.sim_shape[1], 0.4 / 0.9, 1e-15);
}

// Light lost (every bin scaled by 0.9) keeps the shape and fails the joint fractions; light moved
// between rows keeps the per-bin totals and fails the joint fractions alone; light moved between
// bins fails both. At 10^6 rays the expected L1 of six bins is ~1.3e-3.
TEST(LobeComparison, TheShapeSeesBinsTheJointSeesEnergyAndRows) {
  std::vector<double> dim = kModel;
  for (double& v : dim) v *= 0.9;
  const LobeComparison lost = compare_lobes(dim, kModel, 3, 1e6, 1e6, 5.0, 0.0);
  EXPECT_NEAR(lost.shape.l1, 0.0, 1e-15);
  EXPECT_TRUE(lost.shape.holds());
  EXPECT_NEAR(lost.joint.l1, 0.09, 1e-15);
  EXPECT_FALSE(lost.joint.holds()) << lost.joint.threshold;

  std::vector<double> rows = kModel;
  rows[0] -= 0.05, rows[3] += 0.05;
  const LobeComparison by_k = compare_lobes(rows, kModel, 3, 1e6, 1e6, 5.0, 0.0);
  EXPECT_NEAR(by_k.shape.l1, 0.0, 1e-15);
  EXPECT_NEAR(by_k.joint.l1, 0.1, 1e-15);
  EXPECT_FALSE(by_k.joint.holds());

  std::vector<double> bins = kModel;
  bins[0] -= 0.05, bins[1] += 0.05;
  const LobeComparison moved = compare_lobes(bins, kModel, 3, 1e6, 1e6, 5.0, 0.0);
  EXPECT_NEAR(moved.shape.l1, 0.1 / 0.9, 1e-15);
  EXPECT_FALSE(moved.shape.holds());
  EXPECT_FALSE(moved.joint.holds());
}

// The thresholds by hand: expected L1 = sum_b sqrt(2 v_b / pi), sd = sqrt(sum_b (1 - 2/pi) v_b),
// v_b = p_b (1 - p_b) (1/N + 1/G); threshold = expected + sigmas sd + tolerance.
TEST(LobeComparison, ThresholdsByHand) {
  const std::vector<double> p = {0.25, 0.75};
  const double N = 400.0, G = 1e4, sigmas = 3.0, tol = 1e-3;
  const double v = 0.25 * 0.75 * (1.0 / N + 1.0 / G);
  const double mean = 2.0 * std::sqrt(2.0 * v / M_PI), sd = std::sqrt(2.0 * (1.0 - 2.0 / M_PI) * v);
  const L1Test t = l1_test(0.01, p, N, G, sigmas, tol);
  EXPECT_NEAR(t.expected, mean, 1e-15);
  EXPECT_NEAR(t.threshold, mean + sigmas * sd + tol, 1e-15);
  EXPECT_TRUE(t.holds());
  // The albedo: sigmas sqrt(a (1 - a) (1/N + 1/G)) + 1/N + tolerance, a clamped to [0, 1].
  EXPECT_NEAR(albedo_threshold(0.5, 100.0, 100.0, 5.0, 0.0), 5.0 * std::sqrt(0.25 * 0.02) + 0.01, 1e-15);
  EXPECT_NEAR(albedo_threshold(1.5, 100.0, 100.0, 5.0, 1e-3), 0.01 + 1e-3, 1e-15);
}

}  // namespace
}  // namespace vgroove::validation
