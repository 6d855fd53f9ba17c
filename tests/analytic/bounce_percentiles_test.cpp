// Table 2 of Lee et al. 2018 (maximum bounces at the 90/95/99th percentile of D): the rule in
// analytic/bounce_percentiles.h reproduces all 27 printed values, and its closed-form quantiles
// are the quantiles of analytic/ndf.h's D.
#include "vgroove/analytic/bounce_percentiles.h"

#include "tests/stats.h"
#include "vgroove/analytic/brdf_3d.h"
#include "vgroove/analytic/kaleidoscope.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <numbers>

namespace vgroove::analytic {
namespace {

constexpr NdfKind kNdfs[] = {NdfKind::beckmann, NdfKind::phong, NdfKind::ggx};
constexpr double kAlphas[] = {0.5, 0.7, 1.0};
constexpr double kPercentiles[] = {0.90, 0.95, 0.99};
// Lee et al. 2018, Table 2, rows 90/95/99 %, columns Beckmann, Phong, GGX x alpha 0.5, 0.7, 1.0.
constexpr int kTable2[3][9] = {
    {2, 3, 3, 2, 3, 5, 3, 4, 5}, {2, 3, 3, 3, 4, 7, 4, 5, 7}, {3, 3, 4, 3, 5, 16, 8, 12, 16}};

TEST(Table2, ProjectedAreaPercentileAtNormalIncidenceReproducesAll27) {
  for (int r = 0; r < 3; ++r)
    for (int n = 0; n < 3; ++n)
      for (int a = 0; a < 3; ++a)
        EXPECT_EQ(max_bounces_at_percentile(kNdfs[n], kAlphas[a], kPercentiles[r], PercentileMeasure::projected_area),
                  kTable2[r][3 * n + a])
            << ndf_name(kNdfs[n]) << " alpha " << kAlphas[a] << " q " << kPercentiles[r];
}

// A hand value: GGX alpha = 1, q = 0.99: tan^2 = 99, theta_m = atan(sqrt 99) = 84.26 deg, theta_v =
// 11.48 deg, pi / theta_v = 15.68, Eq. (4): floor + 1 = 16.
TEST(Table2, GgxAlphaOneHandValue) {
  const double t = theta_m_quantile(NdfKind::ggx, 1.0, 0.99, PercentileMeasure::projected_area);
  EXPECT_NEAR(std::tan(t), std::sqrt(99.0), 1e-12);
  EXPECT_EQ(bounce_count(0.0, std::numbers::pi - 2.0 * t), 16);
}

// The closed forms invert the projected-area CDF of ndf.h's D: int_0^theta_q 2 pi D cos sin = q.
TEST(Table2, ClosedFormQuantilesInvertTheNdf) {
  for (NdfKind ndf : kNdfs)
    for (double alpha : {0.1, 0.5, 0.7, 1.0, 1.7})
      for (double q : {0.1, 0.5, 0.9, 0.99}) {
        const double t = theta_m_quantile(ndf, alpha, q, PercentileMeasure::projected_area);
        const double mass = vgroove::test_stats::tanh_sinh(
            [&](double x) { return 2.0 * std::numbers::pi * D(ndf, x, alpha) * std::cos(x) * std::sin(x); }, 0.0, t);
        EXPECT_NEAR(mass, q, 1e-10) << ndf_name(ndf) << " alpha " << alpha << " q " << q;
      }
}

// The other readings of "percentile of D" do not reproduce the table (the report shows them).
TEST(Table2, OtherMeasuresDisagreeSomewhere) {
  for (PercentileMeasure m : {PercentileMeasure::solid_angle, PercentileMeasure::flatland}) {
    int agree = 0;
    for (int r = 0; r < 3; ++r)
      for (int n = 0; n < 3; ++n)
        for (int a = 0; a < 3; ++a)
          agree += max_bounces_at_percentile(kNdfs[n], kAlphas[a], kPercentiles[r], m) == kTable2[r][3 * n + a];
    EXPECT_LT(agree, 27) << percentile_measure_name(m);
  }
}

// Quantiles grow with q and with alpha (rougher surfaces, steeper facets).
TEST(Table2, QuantilesAreMonotone) {
  for (NdfKind ndf : kNdfs)
    for (PercentileMeasure m :
         {PercentileMeasure::projected_area, PercentileMeasure::solid_angle, PercentileMeasure::flatland}) {
      EXPECT_LT(theta_m_quantile(ndf, 0.5, 0.9, m), theta_m_quantile(ndf, 0.5, 0.99, m));
      EXPECT_LT(theta_m_quantile(ndf, 0.5, 0.9, m), theta_m_quantile(ndf, 0.7, 0.9, m));
      EXPECT_GT(theta_m_quantile(ndf, 0.5, 0.9, m), 0.0);
      EXPECT_LT(theta_m_quantile(ndf, 0.5, 0.99, m), 0.5 * std::numbers::pi);
    }
}

// Why the rule bounds the light's percentile, and by how much. At normal incidence every groove's
// rays land on its facets in the projected-area measure (the fraction groove_cdf gives) and make
// N - 1 or N reflections, N = floor(pi / theta_v) + 1 non-decreasing in theta_m; so with N0 the
// rule's N at the q-quantile theta_q, P(b <= N0) >= P(theta_m <= theta_q) = q. Here P(b <= N0) by
// quadrature: the grooves with N <= N0 whole, those with N = N0 + 1 for the share of their rays
// that make N0 (Eq. 6 at theta_i = 0; f_b = 0, so every ray aimed at a facet meets it first). The
// margin P(b <= N0) - q is what a traced percentile's sampling error must exceed to show more than
// N0: smallest 0.00123 (GGX and Phong alpha 1, 99 %: 3.4 standard errors at the suite's 200,000
// rays on 100,000 grooves), 0.00183 (GGX 0.5, 99 %: 5.2), 0.00254 (GGX 0.7, 99 %: 7.6), at least
// 0.005 elsewhere; at a few rays it is exceeded (CliTable2.TheTracedPercentileExceedsTheRuleAtFewRays).
// Seen failing with N taken as floor(pi / theta_v) in the quadrature.
TEST(Table2, TheRuleBoundsTheLightsPercentileByTheseMargins) {
  const double pi = std::numbers::pi;
  double smallest = 1.0;
  for (int r = 0; r < 3; ++r)
    for (int n = 0; n < 3; ++n)
      for (int a = 0; a < 3; ++a) {
        const NdfKind ndf = kNdfs[n];
        const double alpha = kAlphas[a], q = kPercentiles[r];
        const int N0 = max_bounces_at_percentile(ndf, alpha, q, PercentileMeasure::projected_area);
        // N = N0 up to theta_v = pi / N0, N0 + 1 down to pi / (N0 + 1).
        const double c0 = groove_cdf(ndf, alpha, 0.5 * (pi - pi / N0));
        const double c1 = groove_cdf(ndf, alpha, 0.5 * (pi - pi / (N0 + 1)));
        double p0 = c0;
        const int m = 20000;
        for (int j = 0; j < m; ++j) {
          const double theta_m = groove_cdf_inverse(ndf, alpha, c0 + (c1 - c0) * (j + 0.5) / m);
          const FacetPrediction p = G_kaleidoscopic(0.0, pi - 2.0 * theta_m, FacetSide::left);
          ASSERT_TRUE(p.lit);
          ASSERT_EQ(p.more.n, N0 + 1);
          p0 += (c1 - c0) / m * (p.fewer.n <= N0 ? p.fewer.G : 0.0);
        }
        EXPECT_GE(p0, q) << ndf_name(ndf) << " alpha " << alpha << " q " << q;
        smallest = std::min(smallest, p0 - q);
        const bool tight = q == 0.99 && (ndf == NdfKind::ggx || (ndf == NdfKind::phong && alpha == 1.0));
        if (!tight) {
          EXPECT_GE(p0 - q, 0.005) << ndf_name(ndf) << " alpha " << alpha << " q " << q;
        }
      }
  EXPECT_NEAR(smallest, 0.00123, 1e-5);
}

}  // namespace
}  // namespace vgroove::analytic
