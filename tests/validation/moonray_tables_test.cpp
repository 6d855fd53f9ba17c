// Tests of DreamWorks MoonRay's published albedo tables as the energy audit reads them
// (validation/energy_formulas.h, feed moonray_table; data/reference/moonray_reflection_albedo.json):
// - the lookup is ReflectionAlbedo's: the ceiling column in cos, linear between roughness rows;
// - the hemispherical integral of the step table is the sum over its columns (hand-derived weights);
// - the tables are Monte Carlo estimates of Smith's *separable* single-scattering albedo (the lobes
//   of MoonRay's BsdfCookTorrance.cc), not of the height-correlated one: what the published values
//   say against the exact quadrature;
// - the compensated albedo is the Kulla-Conty lobe integrated over the light's hemisphere, and
//   MoonRay adds it only where its input roughness sqrt(alpha) exceeds 0.5.
#include "vgroove/analytic/albedo_single.h"
#include "vgroove/validation/energy_formulas.h"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <string>

using namespace vgroove;
using namespace vgroove::validation;

namespace {
const MoonrayTables& file_tables() {
  static const MoonrayTables t =
      read_moonray_tables(std::string(VGROOVE_SOURCE_DIR) + "/data/reference/moonray_reflection_albedo.json");
  return t;
}
double at(const std::vector<double>& v, int row, int col) { return v[static_cast<std::size_t>(row * 33 + col)]; }
}  // namespace

TEST(MoonrayTables, LookupIsMoonRaysIndexing) {
  const MoonrayTables& t = file_tables();
  EXPECT_EQ(published_moonray_tables().ggx_E, t.ggx_E);  // the compiled-in copy is the file's
  EXPECT_EQ(published_moonray_tables().beckmann_one_minus_E_avg, t.beckmann_one_minus_E_avg);
  for (NdfKind ndf : {NdfKind::ggx, NdfKind::beckmann})
    for (int i : {0, 7, 20, 32}) {
      const double r = i / 32.0, alpha = r * r;
      for (int j : {1, 5, 16, 32}) {
        const double want = static_cast<float>(at(t.E(ndf), i, j));
        EXPECT_EQ(moonray_E(t, ndf, alpha, j / 32.0), want) << i << " " << j;               // on the column
        EXPECT_EQ(moonray_E(t, ndf, alpha, (j - 1) / 32.0 + 1e-3), want) << i << " " << j;  // ceil from below
        if (j < 32) {  // just past the column: the next one
          EXPECT_EQ(moonray_E(t, ndf, alpha, j / 32.0 + 1e-3), static_cast<float>(at(t.E(ndf), i, j + 1)));
        }
      }
      EXPECT_EQ(moonray_E(t, ndf, alpha, 0.0), 0.0);  // column 0 holds 0
      EXPECT_EQ(moonray_one_minus_E_avg(t, ndf, alpha),
                static_cast<float>(t.one_minus_E_avg(ndf)[static_cast<std::size_t>(i)]));
    }
  // Half-way between rows 20 and 21: the mean of the two (float arithmetic).
  const double r = 20.5 / 32.0;
  EXPECT_NEAR(moonray_E(t, NdfKind::ggx, r * r, 0.5), 0.5 * (at(t.ggx_E, 20, 16) + at(t.ggx_E, 21, 16)), 2e-7);
  EXPECT_NEAR(moonray_one_minus_E_avg(t, NdfKind::beckmann, r * r),
              0.5 * (t.beckmann_one_minus_E_avg[20] + t.beckmann_one_minus_E_avg[21]), 2e-7);
}

// 2 int_0^1 (1 - E(x)) x dx with E constant on ((j - 1)/32, j/32]: the midpoint rule on 100 steps per
// column is exact (the integrand is linear on each step), so it must give the column sum to rounding.
TEST(MoonrayTables, MissingAverageIsTheStepTablesIntegral) {
  const MoonrayTables& t = file_tables();
  for (NdfKind ndf : {NdfKind::ggx, NdfKind::beckmann})
    for (double alpha : {0.3, 0.55, 1.0}) {
      const int steps = 3200;
      double sum = 0.0;
      for (int s = 0; s < steps; ++s) {
        const double x = (s + 0.5) / steps;
        sum += 2.0 * (1.0 - moonray_E(t, ndf, alpha, x)) * x / steps;
      }
      EXPECT_NEAR(moonray_missing_average(t, ndf, alpha), sum, 1e-12) << alpha;
    }
}

TEST(MoonrayTables, CompensatedAlbedoIsTheLobeOverTheLightsHemisphere) {
  const MoonrayTables& t = published_moonray_tables();
  FormulaVariant v;
  for (const FormulaVariant& x : formula_variants())
    if (x.id == "kulla_conty@moonray_table") v = x;
  ASSERT_EQ(v.formula, "kulla_conty");
  const SingleScattering s{0.7, 0.0, 0.0, 0.6};  // not read by this feed
  const double F0 = 0.9, F_avg = 0.93, E_F = 0.62, mu = 0.4;
  const ChannelValues c{F0, F_avg, E_F};
  for (NdfKind ndf : {NdfKind::ggx, NdfKind::beckmann}) {
    const double alpha = 0.64;  // r = 0.8
    EngineValues e{};
    e.moonray_E = moonray_E(t, ndf, alpha, mu);
    e.moonray_one_minus_E_avg = moonray_one_minus_E_avg(t, ndf, alpha);
    e.moonray_missing_average = moonray_missing_average(t, ndf, alpha);
    e.moonray_compensates = moonray_compensates(alpha);
    ASSERT_TRUE(e.moonray_compensates);
    // MoonRay's lobe (1 - E(mu)) (1 - E(mu_i)) / (pi (1 - E_avg)) F_avg^2 E_avg / (1 - F_avg (1 -
    // E_avg)) times cos(theta_i), integrated over the light's hemisphere by a (theta, phi) grid.
    const double Eavg = 1.0 - e.moonray_one_minus_E_avg;
    const double Fms = F_avg * F_avg * Eavg / (1.0 - F_avg * (1.0 - Eavg));
    const double K = (1.0 - e.moonray_E) / (std::numbers::pi * e.moonray_one_minus_E_avg) * Fms;
    const int n = 1 << 16;
    const double h = (std::numbers::pi / 2) / n;
    double lobe = 0.0;
    for (int k = 0; k < n; ++k) {
      const double theta = (k + 0.5) * h, mu_i = std::cos(theta);
      lobe += K * (1.0 - moonray_E(t, ndf, alpha, mu_i)) * mu_i * std::sin(theta) * 2.0 * std::numbers::pi * h;
    }
    // The grid's error: at each column's jump the midpoint rule misplaces at most one step of
    // K |jump| 2 pi mu sin(theta) (<= K |jump| pi); the smooth part's error is O(h^2).
    double variation = 0.0;
    for (int j = 1; j < 32; ++j)
      variation += std::abs(moonray_E(t, ndf, alpha, (j + 0.5) / 32.0) - moonray_E(t, ndf, alpha, (j - 0.5) / 32.0));
    const double step_bound = K * std::numbers::pi * h * variation + 1e-8;
    EXPECT_NEAR(compensated_albedo(v, s, e, c, alpha, mu), E_F + lobe, step_bound);
    // Broken: the lobe's own integral taken as 1 - E_avg (the identity that holds for the exact E
    // and E_avg, not for the tables) misses by more than the grid's error.
    EngineValues broken = e;
    broken.moonray_missing_average = e.moonray_one_minus_E_avg;
    EXPECT_GT(std::abs(compensated_albedo(v, s, broken, c, alpha, mu) - (E_F + lobe)), step_bound) << ndf_name(ndf);
  }
  // MoonRay adds the lobe only where sqrt(alpha) > 0.5: at r = 0.5 the albedo is f_ss's alone.
  EXPECT_FALSE(moonray_compensates(0.25));
  EXPECT_TRUE(moonray_compensates(0.51 * 0.51));
  EngineValues e{};
  e.moonray_E = moonray_E(t, NdfKind::ggx, 0.25, mu);
  e.moonray_one_minus_E_avg = moonray_one_minus_E_avg(t, NdfKind::ggx, 0.25);
  e.moonray_missing_average = moonray_missing_average(t, NdfKind::ggx, 0.25);
  e.moonray_compensates = false;
  EXPECT_EQ(compensated_albedo(v, s, e, c, 0.25, mu), E_F);
}

// The published values against the quadrature (analytic/albedo_single.h, bound 1e-8), at the rows
// r = i / 32 (alpha = max(r^2, 0.001), MoonRay's floor) and columns mu = j / 32 >= 1/32, where the
// table is below 0.999 (its saturated texels say nothing). The table's own noise s, from its second
// differences along mu (white noise gives var(E[j-1] - 2 E[j] + E[j+1]) = 6 s^2 where the curve is
// smooth). Smith's separable G2 (MoonRay's lobes) fits it better than the height-correlated one,
// and at grazing (mu <= 1/8) the table lies below it by far more than its noise.
TEST(MoonrayTables, TablesFollowSmithsSeparableAlbedoAndFallShortAtGrazing) {
  const MoonrayTables& t = published_moonray_tables();
  analytic::AlbedoOptions opt;
  opt.tol = 1e-8;
  for (NdfKind ndf : {NdfKind::ggx, NdfKind::beckmann}) {
    const std::vector<double>& E = t.E(ndf);
    double d2 = 0.0, n2 = 0.0, sep = 0.0, hc = 0.0, n = 0.0, sep_max = 0.0, grazing = 0.0, n_grazing = 0.0;
    for (int i = 8; i <= 32; i += 4) {
      const double r = i / 32.0, alpha = std::max(r * r, 0.001);
      for (int j = 1; j <= 32; ++j) {
        const double x = at(E, i, j);
        if (j >= 2 && j <= 31 && at(E, i, j + 1) < 0.999) {
          const double d = at(E, i, j - 1) - 2.0 * x + at(E, i, j + 1);
          d2 += d * d, n2 += 1.0;
        }
        if (!(x < 0.999)) continue;
        const double mu = j / 32.0;
        const double s =
            x - analytic::albedo_single({ndf, analytic::MaskingKind::smith_separable}, alpha, mu, opt).value;
        const double h =
            x - analytic::albedo_single({ndf, analytic::MaskingKind::smith_height_correlated}, alpha, mu, opt).value;
        sep += s * s, hc += h * h, n += 1.0, sep_max = std::max(sep_max, std::abs(s));
        if (j <= 4) grazing += s, n_grazing += 1.0;
      }
    }
    const double noise = std::sqrt(d2 / n2 / 6.0), rms_sep = std::sqrt(sep / n), rms_hc = std::sqrt(hc / n);
    std::printf(
        "%s: %g texels, noise sd %.5f; separable rms %.5f max %.5f, mu <= 1/8 mean %+.5f (%g texels); "
        "height-correlated rms %.5f\n",
        ndf_name(ndf), n, noise, rms_sep, sep_max, grazing / n_grazing, n_grazing, rms_hc);
    EXPECT_LT(rms_sep, rms_hc) << ndf_name(ndf);
    EXPECT_LT(grazing / n_grazing, -5.0 * noise / std::sqrt(n_grazing)) << ndf_name(ndf);
  }
}
