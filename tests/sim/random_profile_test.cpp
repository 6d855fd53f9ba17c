// Tests of sim/random_profile.h: the profiles close their period exactly, are reproducible from
// their seed, and have the slope statistics they are built for, checked against values derived
// here by hand (the facet-normal distribution against analytic D2 is a chi-square in
// tests/validation/profile_ndf_test.cpp, which may include analytic/).
//
// Statistics over independent samples: segments 3 correlation lengths apart (Gaussian slope
// correlation there (1 - 2 x 9) e^-9 = -0.002) from independent realizations; tolerances 4.5
// standard errors, the standard errors computed from the samples' own spread.
#include "vgroove/sim/random_profile.h"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <vector>

namespace vgroove::sim {
namespace {

constexpr int kSpl = 16;  // samples per correlation length

RandomProfileOptions options(NdfKind ndf, double alpha, int segments, std::uint64_t seed) {
  RandomProfileOptions o;
  o.ndf = ndf;
  o.alpha = alpha;
  o.segments = segments;
  o.samples_per_length = kSpl;
  o.seed = seed;
  return o;
}

double slope(const Polyline& p, int j) {
  return (p.y[static_cast<std::size_t>(j) + 1] - p.y[static_cast<std::size_t>(j)]) /
         (p.x[static_cast<std::size_t>(j) + 1] - p.x[static_cast<std::size_t>(j)]);
}

struct MeanSe {
  double mean = 0.0, se = 0.0;
};
MeanSe mean_se(const std::vector<double>& v) {
  double m = 0.0;
  for (double x : v) m += x;
  m /= static_cast<double>(v.size());
  double var = 0.0;
  for (double x : v) var += (x - m) * (x - m);
  var /= static_cast<double>(v.size() - 1);
  return {m, std::sqrt(var / static_cast<double>(v.size()))};
}

TEST(RandomProfile, ClosesItsPeriodExactlyAndIsReproducible) {
  for (NdfKind ndf : {NdfKind::beckmann, NdfKind::ggx}) {
    const Polyline p = make_random_profile(options(ndf, 0.5, 4096, 9));
    ASSERT_EQ(p.segments(), 4096);
    EXPECT_EQ(p.period, 256.0);
    EXPECT_EQ(p.x[4096], 256.0);
    EXPECT_EQ(p.y[4096], p.y[0]);
    for (int v = 0; v <= 4096; ++v) EXPECT_EQ(p.x[static_cast<std::size_t>(v)], v / 16.0);
    const Polyline q = make_random_profile(options(ndf, 0.5, 4096, 9));
    EXPECT_EQ(p.y, q.y);
    const Polyline r = make_random_profile(options(ndf, 0.5, 4096, 10));
    EXPECT_NE(p.y, r.y);
  }
}

TEST(RandomProfile, BeckmannSlopesAreGaussianOfVarianceAlphaSquaredOverTwo) {
  for (double alpha : {0.1, 0.5, 1.0}) {
    std::vector<double> s2, s4;
    for (std::uint64_t seed = 0; seed < 8; ++seed) {
      const Polyline p = make_random_profile(options(NdfKind::beckmann, alpha, 1 << 15, seed));
      for (int j = 0; j < p.segments(); j += 3 * kSpl) {
        const double s = slope(p, j);
        s2.push_back(s * s);
        s4.push_back(s * s * s * s);
      }
    }
    // E s^2 = alpha^2 / 2; E s^4 = 3 (alpha^2 / 2)^2 (Gaussian kurtosis 3).
    const double v = 0.5 * alpha * alpha;
    const MeanSe m2 = mean_se(s2), m4 = mean_se(s4);
    EXPECT_NEAR(m2.mean, v, 4.5 * m2.se) << "alpha=" << alpha;
    EXPECT_NEAR(m4.mean, 3.0 * v * v, 4.5 * m4.se) << "alpha=" << alpha;
    // Power: a 5 % error in the slope deviation would be seen.
    EXPECT_GT(std::abs(m2.mean - 1.1025 * v), 4.5 * m2.se) << "alpha=" << alpha;
  }
}

TEST(RandomProfile, BeckmannAutocorrelationIsGaussianOfUnitLength) {
  // Heights: rho(r) = exp(-r^2) (l = 1): at r = l, e^-1; at r = l/2, e^-1/4. Segment slopes are
  // differences of heights: their correlation at lag m is
  //   (2 rho(m dx) - rho((m+1) dx) - rho((m-1) dx)) / (2 - 2 rho(dx)).
  auto rho = [](double r) { return std::exp(-r * r); };
  const double dx = 1.0 / kSpl;
  auto slope_corr = [&](int m) {
    return (2 * rho(m * dx) - rho((m + 1) * dx) - rho((m - 1) * dx)) / (2 - 2 * rho(dx));
  };
  std::vector<double> h1, h_half, s_half, s1;
  for (std::uint64_t seed = 0; seed < 16; ++seed) {
    const Polyline p = make_random_profile(options(NdfKind::beckmann, 0.7, 1 << 14, 100 + seed));
    const int n = p.segments();
    double hh = 0, h_l = 0, h_h = 0, ss = 0, s_h = 0, s_l = 0;
    for (int j = 0; j < n; ++j) {
      const double y = p.y[static_cast<std::size_t>(j)];
      hh += y * y;
      h_l += y * p.y[static_cast<std::size_t>((j + kSpl) % n)];
      h_h += y * p.y[static_cast<std::size_t>((j + kSpl / 2) % n)];
      const double s = slope(p, j);
      ss += s * s;
      s_h += s * slope(p, (j + kSpl / 2) % n);
      s_l += s * slope(p, (j + kSpl) % n);
    }
    h1.push_back(h_l / hh), h_half.push_back(h_h / hh), s_half.push_back(s_h / ss), s1.push_back(s_l / ss);
  }
  const MeanSe a = mean_se(h1), b = mean_se(h_half), c = mean_se(s_half), d = mean_se(s1);
  EXPECT_NEAR(a.mean, std::exp(-1.0), 4.5 * a.se);
  EXPECT_NEAR(b.mean, std::exp(-0.25), 4.5 * b.se);
  EXPECT_NEAR(c.mean, slope_corr(kSpl / 2), 4.5 * c.se);
  EXPECT_NEAR(d.mean, slope_corr(kSpl), 4.5 * d.se);
  // The continuous slope correlation (1 - 2 r^2) e^-r^2: 0.3894 at l/2, -0.3679 at l; the
  // polyline's differences are within 0.5 % of it at 16 samples per length.
  EXPECT_NEAR(slope_corr(kSpl / 2), 0.5 * std::exp(-0.25), 0.005);
  EXPECT_NEAR(slope_corr(kSpl), -std::exp(-1.0), 0.005);
  // Power: a correlation length 10 % longer is seen (rho(l / 1.1) = 0.437).
  EXPECT_GT(std::abs(a.mean - std::exp(-1.0 / 1.21)), 4.5 * a.se);
}

TEST(RandomProfile, GgxSlopeQuantileTransform) {
  // Q(Phi(z)) with Q(u) = alpha (2u - 1) / (2 sqrt(u (1 - u))): 0 at z = 0; at the upper
  // quartile (u = 3/4) alpha / sqrt 3; odd in z; and deep in the tails u (1 - u) ~ Phi(-|z|).
  const double alpha = 0.8;
  EXPECT_EQ(ggx_slope_from_normal(0.0, alpha), 0.0);
  EXPECT_NEAR(ggx_slope_from_normal(0.6744897501960817, alpha), alpha / std::sqrt(3.0), 1e-14);
  for (double z : {0.3, 2.0, 6.0, 9.0}) {
    EXPECT_EQ(ggx_slope_from_normal(-z, alpha), -ggx_slope_from_normal(z, alpha)) << z;
    const double tail = 0.5 * std::erfc(z / std::numbers::sqrt2);
    const double u = 1.0 - tail;
    EXPECT_NEAR(ggx_slope_from_normal(z, alpha), alpha * (u - tail) / (2.0 * std::sqrt(u * tail)),
                1e-12 * ggx_slope_from_normal(z, alpha))
        << z;
  }
  double prev = -1e300;
  for (double z = -8.0; z <= 8.0; z += 0.01) {
    const double s = ggx_slope_from_normal(z, alpha);
    EXPECT_GT(s, prev) << z;
    prev = s;
  }
}

TEST(RandomProfile, GgxProfileIsTheTransformedProcessThenItsMirror) {
  const RandomProfileOptions o = options(NdfKind::ggx, 0.4, 2048, 5);
  const Polyline p = make_random_profile(o);
  const std::vector<double> z = gaussian_slope_process(2048, kSpl, 5);
  for (int j = 0; j < 1024; ++j) {
    EXPECT_NEAR(slope(p, j), ggx_slope_from_normal(z[static_cast<std::size_t>(j)], 0.4),
                1e-9 * (1.0 + std::abs(slope(p, j))))
        << j;
    EXPECT_EQ(p.y[static_cast<std::size_t>(1024 + j)], p.y[static_cast<std::size_t>(1024 - j)]) << j;
  }
}

TEST(RandomProfile, GaussianSlopeProcessIsStandardNormal) {
  std::vector<double> z2;
  double z_sum = 0.0;
  for (std::uint64_t seed = 0; seed < 8; ++seed) {
    const std::vector<double> z = gaussian_slope_process(1 << 15, kSpl, seed);
    for (std::size_t j = 0; j < z.size(); j += 3 * kSpl) z2.push_back(z[j] * z[j]), z_sum += z[j];
  }
  const MeanSe m = mean_se(z2);
  EXPECT_NEAR(m.mean, 1.0, 4.5 * m.se);
  EXPECT_NEAR(z_sum / static_cast<double>(z2.size()), 0.0, 4.5 / std::sqrt(static_cast<double>(z2.size())));
}

}  // namespace
}  // namespace vgroove::sim
