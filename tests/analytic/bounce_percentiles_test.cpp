// Table 2 of Lee et al. 2018 (maximum bounces at the 90/95/99th percentile of D): the rule in
// analytic/bounce_percentiles.h reproduces all 27 printed values, and its closed-form quantiles
// are the quantiles of analytic/ndf.h's D.
#include "vgroove/analytic/bounce_percentiles.h"

#include "tests/stats.h"
#include "vgroove/analytic/kaleidoscope.h"

#include <gtest/gtest.h>

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

}  // namespace
}  // namespace vgroove::analytic
