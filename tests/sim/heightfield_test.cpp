// Tests of sim/heightfield.h and sim/heightfield_hierarchy.h: periodic Gaussian heightfields with
// Beckmann slopes, the validation fields, and the min-max levels.
//
// Statistics of a Gaussian field, with tolerances derived from its correlation (Isserlis): for a
// zero-mean stationary Gaussian process X on the n x n torus with covariance K(r), the mean of
// X^2 over the n^2 points has the variance (2 / n^2) sum_r K(r)^2, and the mean of X(p) X(p + L)
// the variance (1 / n^2) sum_r (K(r)^2 + K(r + L) K(r - L)). K is the height covariance C (rms
// height, correlation) or the covariance of the finite differences (slopes):
//   K_x(dx, dy) = 2 C(dx, dy) - C(dx + 1, dy) - C(dx - 1, dy).
// The expected values come from the parameters by the header's formulas, written here again:
// slope variance alpha^2 / 2 per axis (Beckmann), rms height sigma, C(L, 0) = sigma^2 exp(-L^2 /
// l_x^2). Sums over 8 seeds; 5 sigma.
//
// The triangles' slopes against Beckmann's P22 (equal-probability bins of each axis' normal law of
// variance alpha^2 / 2): per-bin z from 16 independent fields (the spread between fields is the
// bin's variance: the triangles of one field are correlated), Student t with 15 degrees of
// freedom, Bonferroni over the bins.
#include "vgroove/sim/heightfield.h"
#include "vgroove/sim/heightfield_hierarchy.h"

#include <gtest/gtest.h>
#include <boost/math/distributions/normal.hpp>
#include <boost/math/distributions/students_t.hpp>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <functional>
#include <numbers>
#include <vector>

namespace vgroove::sim {
namespace {

struct Case {
  double alpha_x, alpha_y, l_x;
};

// sigma and l_y from the header's formulas (independent of the library's code).
void expected_parameters(const Case& c, double& sigma, double& l_y) {
  sigma = c.alpha_x / (2.0 * std::sqrt(1.0 - std::exp(-1.0 / (c.l_x * c.l_x))));
  l_y = 1.0 / std::sqrt(-std::log(1.0 - c.alpha_y * c.alpha_y / (4.0 * sigma * sigma)));
}

// sum over lags of K(r) K(r + L), K from C over a window wide enough for C to vanish.
double lag_sum(const std::function<double(double, double)>& K, double reach, int Lx, int Ly) {
  const int w = static_cast<int>(std::ceil(reach));
  double s = 0.0;
  for (int dy = -w; dy <= w; ++dy)
    for (int dx = -w; dx <= w; ++dx) s += K(dx, dy) * K(dx + Lx, dy + Ly);
  return s;
}

class GaussianHeightfieldStats : public testing::TestWithParam<Case> {};

TEST_P(GaussianHeightfieldStats, SlopeVarianceRmsHeightAndCorrelationMatchTheParameters) {
  const Case c = GetParam();
  double sigma = 0.0, l_y = 0.0;
  expected_parameters(c, sigma, l_y);
  const GaussianHeightfieldParameters p = gaussian_heightfield_parameters({256, c.alpha_x, c.alpha_y, c.l_x, 0});
  EXPECT_NEAR(p.sigma, sigma, 1e-12 * sigma);
  EXPECT_NEAR(p.l_y, l_y, 1e-9 * l_y);
  const int n = 256, seeds = 8;
  const int L = static_cast<int>(std::lround(c.l_x));
  double sx2 = 0.0, sy2 = 0.0, h2 = 0.0, hh = 0.0;
  for (int seed = 0; seed < seeds; ++seed) {
    const Heightfield f = make_gaussian_heightfield({n, c.alpha_x, c.alpha_y, c.l_x, static_cast<std::uint64_t>(seed)});
    for (int j = 0; j < n; ++j)
      for (int i = 0; i < n; ++i) {
        const double h = f.height(i, j);
        sx2 += (f.height(i + 1, j) - h) * (f.height(i + 1, j) - h);
        sy2 += (f.height(i, j + 1) - h) * (f.height(i, j + 1) - h);
        h2 += h * h;
        hh += h * f.height(i + L, j);
      }
  }
  const double cells = static_cast<double>(n) * n * seeds;
  sx2 /= cells;
  sy2 /= cells;
  h2 /= cells;
  hh /= cells;
  auto C = [&](double dx, double dy) {
    return sigma * sigma * std::exp(-dx * dx / (c.l_x * c.l_x) - dy * dy / (l_y * l_y));
  };
  auto Kx = [&](double dx, double dy) { return 2.0 * C(dx, dy) - C(dx + 1, dy) - C(dx - 1, dy); };
  auto Ky = [&](double dx, double dy) { return 2.0 * C(dx, dy) - C(dx, dy + 1) - C(dx, dy - 1); };
  const double reach = 7.0 * std::max(c.l_x, l_y);
  const double sd_sx2 = std::sqrt(2.0 / cells * lag_sum(Kx, reach, 0, 0));
  const double sd_sy2 = std::sqrt(2.0 / cells * lag_sum(Ky, reach, 0, 0));
  const double sd_h2 = std::sqrt(2.0 / cells * lag_sum(C, reach, 0, 0));
  // sum_r C(r + L) C(r - L) = sum_r C(r) C(r + 2L) (the shift r -> r + L).
  const double sd_hh = std::sqrt((lag_sum(C, reach, 0, 0) + lag_sum(C, reach, 2 * L, 0)) / cells);
  EXPECT_NEAR(sx2, 0.5 * c.alpha_x * c.alpha_x, 5.0 * sd_sx2) << "slope variance along x";
  EXPECT_NEAR(sy2, 0.5 * c.alpha_y * c.alpha_y, 5.0 * sd_sy2) << "slope variance along y";
  EXPECT_NEAR(h2, sigma * sigma, 5.0 * sd_h2) << "mean square height";
  EXPECT_NEAR(hh, C(L, 0), 5.0 * sd_hh) << "autocorrelation at lag " << L;
  // The tolerances are meaningful: a few percent of the values, not their size.
  EXPECT_LT(5.0 * sd_sx2, 0.1 * 0.5 * c.alpha_x * c.alpha_x);
}

INSTANTIATE_TEST_SUITE_P(Fields, GaussianHeightfieldStats,
                         testing::Values(Case{0.5, 0.5, 8.0}, Case{0.2, 0.2, 4.0}, Case{1.0, 1.0, 6.0},
                                         Case{0.3, 0.6, 8.0}));

// Per-bin z of the triangles' slopes against Beckmann P22 (header).
class GaussianHeightfieldNdf : public testing::TestWithParam<Case> {};

TEST_P(GaussianHeightfieldNdf, TriangleSlopesFollowBeckmann) {
  const Case c = GetParam();
  const int n = 256, fields = 16, bins = 6;
  boost::math::normal_distribution<double> unit;
  std::vector<double> edges(bins + 1);
  for (int b = 0; b <= bins; ++b)
    edges[static_cast<std::size_t>(b)] =
        b == 0 ? -HUGE_VAL : (b == bins ? HUGE_VAL : boost::math::quantile(unit, static_cast<double>(b) / bins));
  auto bin_of = [&](double z) {
    return static_cast<int>(std::upper_bound(edges.begin() + 1, edges.end() - 1, z) - (edges.begin() + 1));
  };
  const double sd_x = c.alpha_x / std::sqrt(2.0), sd_y = c.alpha_y / std::sqrt(2.0);
  std::vector<double> sum(bins * bins, 0.0), sum2(bins * bins, 0.0);
  for (int s = 0; s < fields; ++s) {
    const Heightfield f =
        make_gaussian_heightfield({n, c.alpha_x, c.alpha_y, c.l_x, 1000u + static_cast<std::uint64_t>(s)});
    std::vector<double> count(bins * bins, 0.0);
    for (int j = 0; j < n; ++j)
      for (int i = 0; i < n; ++i) {
        const double h00 = f.height(i, j), h10 = f.height(i + 1, j), h01 = f.height(i, j + 1),
                     h11 = f.height(i + 1, j + 1);
        // lower: (h10 - h00, h11 - h10); upper: (h11 - h01, h01 - h00) (sim/heightfield.h)
        count[static_cast<std::size_t>(bin_of((h10 - h00) / sd_x) * bins + bin_of((h11 - h10) / sd_y))] += 1.0;
        count[static_cast<std::size_t>(bin_of((h11 - h01) / sd_x) * bins + bin_of((h01 - h00) / sd_y))] += 1.0;
      }
    for (std::size_t b = 0; b < count.size(); ++b) {
      const double frac = count[b] / (2.0 * n * n);
      sum[b] += frac;
      sum2[b] += frac * frac;
    }
  }
  const double p = 1.0 / (bins * bins);
  const boost::math::students_t t(fields - 1);
  const double z_max = boost::math::quantile(boost::math::complement(t, 0.001 / (2.0 * bins * bins)));
  for (std::size_t b = 0; b < sum.size(); ++b) {
    const double mean = sum[b] / fields;
    const double var = (sum2[b] - fields * mean * mean) / (fields - 1);
    const double z = (mean - p) / std::sqrt(var / fields);
    EXPECT_LT(std::abs(z), z_max) << "bin (" << b / bins << ", " << b % bins << "): " << mean << " vs " << p;
    // The test resolves the bins: the spread is a few percent of p.
    EXPECT_LT(std::sqrt(var / fields), 0.05 * p);
  }
}

INSTANTIATE_TEST_SUITE_P(Fields, GaussianHeightfieldNdf,
                         testing::Values(Case{0.5, 0.5, 8.0}, Case{1.0, 1.0, 8.0}, Case{0.3, 0.6, 8.0}));

TEST(GaussianHeightfield, IsDeterministicPerSeedAndDiffersBetweenSeeds) {
  const Heightfield a = make_gaussian_heightfield({64, 0.5, 0.5, 4.0, 7});
  const Heightfield b = make_gaussian_heightfield({64, 0.5, 0.5, 4.0, 7});
  const Heightfield c = make_gaussian_heightfield({64, 0.5, 0.5, 4.0, 8});
  EXPECT_EQ(a.h, b.h);
  EXPECT_NE(a.h, c.h);
}

TEST(GaussianHeightfield, OutOfRangeParametersAreRefused) {
  EXPECT_THROW(make_gaussian_heightfield({100, 0.5, 0.5, 4.0, 0}), std::invalid_argument);  // not 2^k
  EXPECT_THROW(make_gaussian_heightfield({64, 0.0, 0.5, 4.0, 0}), std::invalid_argument);
  EXPECT_THROW(make_gaussian_heightfield({64, 0.5, 0.5, 1.5, 0}), std::invalid_argument);  // l < 2
  EXPECT_THROW(make_gaussian_heightfield({64, 0.5, 0.5, 9.0, 0}), std::invalid_argument);  // l > n / 8
  EXPECT_THROW(make_gaussian_heightfield({64, 0.1, 2.0, 4.0, 0}),
               std::invalid_argument);  // alpha_y / alpha_x too large
}

TEST(ValidationHeightfields, FlatAndVGrooveHeights) {
  const Heightfield f = make_flat_heightfield(8, 2.5);
  for (double h : f.h) EXPECT_EQ(h, 2.5);
  const Heightfield g = make_vgroove_heightfield(16, 4, 0.75);
  for (int j = 0; j < 16; ++j) {
    EXPECT_EQ(g.height(0, j), 3.0);  // ridge
    EXPECT_EQ(g.height(4, j), 0.0);  // bottom
    EXPECT_EQ(g.height(6, j), 1.5);
    EXPECT_EQ(g.height(16, j), 3.0);  // periodic
    EXPECT_EQ(g.height(-4, j), 0.0);
  }
  EXPECT_THROW(make_vgroove_heightfield(16, 3, 1.0), std::invalid_argument);
}

TEST(HeightfieldHierarchy, EveryLevelBoundsTheCellsBelowIt) {
  const Heightfield f = make_gaussian_heightfield({32, 0.7, 0.4, 2.0, 3});
  const HeightfieldHierarchy m = make_heightfield_hierarchy(f);
  ASSERT_EQ(m.levels, 6);
  for (int k = 0; k < m.levels; ++k) {
    const int s = 32 >> k, size = 1 << k;
    for (int j = 0; j < s; ++j)
      for (int i = 0; i < s; ++i) {
        double lo = HUGE_VAL, hi = -HUGE_VAL;
        for (int y = j * size; y <= (j + 1) * size; ++y)
          for (int x = i * size; x <= (i + 1) * size; ++x) {
            lo = std::min(lo, f.height(x, y));
            hi = std::max(hi, f.height(x, y));
          }
        EXPECT_EQ(m.node(k, i, j).lo, lo) << k << " " << i << " " << j;
        EXPECT_EQ(m.node(k, i, j).hi, hi) << k << " " << i << " " << j;
      }
  }
}

TEST(HeightfieldMemory, BytesPerCellAsStated) {
  // 8 (heights) + 16 * (1 + 1/4 + ...) = 29.33 bytes per cell; 4096^2: 492 MB.
  EXPECT_NEAR(heightfield_bytes(4096) / (4096.0 * 4096.0), 8.0 + 16.0 * 4.0 / 3.0, 1e-6);
  EXPECT_NEAR(heightfield_bytes(4096) / 1e6, 492.0, 1.0);
}

}  // namespace
}  // namespace vgroove::sim
