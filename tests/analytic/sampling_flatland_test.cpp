// Tests of the flatland V-groove sampler (analytic/sampling_flatland.h), as sampling_3d_test.cpp
// for 3D, plus: the single-pass flatland BRDF equals brdf_flatland.h's per-k sum.
#include "vgroove/analytic/sampling_flatland.h"

#include "vgroove/analytic/brdf_flatland.h"
#include "vgroove/analytic/hemisphere_quadrature.h"
#include "vgroove/common/angles.h"

#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <numbers>
#include <random>

namespace vgroove::analytic {
namespace {

constexpr NdfKind kNdfs[] = {NdfKind::beckmann, NdfKind::ggx, NdfKind::phong};
constexpr FacetStrategy kStrategies[] = {FacetStrategy::printed, FacetStrategy::vndf, FacetStrategy::smith_vndf};

std::array<double, 4> uniforms(std::mt19937_64& g) {
  std::uniform_real_distribution<double> U(0.0, 1.0);
  return {U(g), U(g), U(g), U(g)};
}

// rho2 cos from the single pass over the paths (the one the samplers' weights use) against
// flatland_brdf_reference (brdf_flatland.cpp: per k, every m, Eq. 6 through G_kaleidoscopic). 1e-10: the
// single pass writes Eq. 6's widths as products of sines (kaleidoscope_solutions.h), which keep
// their relative accuracy where the ends nearly meet; the reference's differences of sines lose
// up to ~1e-11 there (brdf_3d.cpp measured 3e-11 for the same form against long double).
TEST(SamplingFlatland, SinglePassBrdfIsFlatlandBrdf) {
  std::mt19937_64 g(51);
  std::uniform_real_distribution<double> U(-1.0, 1.0);
  for (int trial = 0; trial < 3000; ++trial) {
    const NdfKind ndf = kNdfs[trial % 3];
    const double alpha = 0.05 + 0.75 * (U(g) + 1.0);
    const double ti = 0.5 * std::numbers::pi * 0.999 * U(g), to = 0.5 * std::numbers::pi * 0.999 * U(g);
    const double a = vgroove_pdf_and_brdf_flatland(ti, to, ndf, alpha, SamplerOptions{FacetStrategy::vndf, 24}).rho_cos;
    const double b = flatland_brdf_reference(ndf, alpha, ti, to, 24) * std::cos(to);
    EXPECT_NEAR(a, b, 1e-10 * b) << ndf_name(ndf) << " alpha=" << alpha << " theta_i=" << ti << " theta_o=" << to;
  }
}

TEST(SamplingFlatland, VcavityPdfIsTheBrdfTimesCosine) {
  std::mt19937_64 g(52);
  std::uniform_real_distribution<double> U(-1.0, 1.0);
  for (int trial = 0; trial < 3000; ++trial) {
    const NdfKind ndf = kNdfs[trial % 3];
    const double alpha = 0.05 + 0.75 * (U(g) + 1.0);
    const double ti = 0.5 * std::numbers::pi * U(g), to = 0.5 * std::numbers::pi * U(g);
    const SamplerOptions opt{FacetStrategy::vndf, 64};
    const PdfAndBrdf2 e = vgroove_pdf_and_brdf_flatland(ti, to, ndf, alpha, opt);
    EXPECT_NEAR(e.pdf, e.rho_cos, 1e-13 * e.rho_cos) << trial;
  }
}

TEST(SamplingFlatland, WeightIsEvalCosOverPdf) {
  std::mt19937_64 g(53);
  std::uniform_real_distribution<double> U(0.0, 1.0);
  for (FacetStrategy st : kStrategies)
    for (NdfKind ndf : kNdfs) {
      if (!strategy_supports(st, ndf, true)) continue;
      int returned = 0;
      for (int trial = 0; trial < 500; ++trial) {
        const double alpha = 0.05 + 1.5 * U(g), ti = (U(g) - 0.5) * std::numbers::pi;
        const SamplerOptions opt{st, 32};
        const VgrooveSampleFlatland s = sample_vgroove_flatland(ti, uniforms(g), ndf, alpha, opt);
        if (s.k == 0) continue;
        ++returned;
        const double pdf = vgroove_pdf_flatland(ti, s.theta_o, ndf, alpha, opt);
        const double eval = flatland_brdf(ndf, alpha, ti, s.theta_o, opt.max_k);
        EXPECT_NEAR(s.pdf, pdf, 1e-12 * pdf);
        EXPECT_NEAR(s.weight, eval * std::cos(s.theta_o) / pdf, 1e-12 * s.weight)
            << strategy_name(st) << " " << ndf_name(ndf) << " trial " << trial;
        EXPECT_GT(vgroove_pdf_flatland_k(ti, s.theta_o, ndf, alpha, opt, s.k, s.k), 0.0);
      }
      EXPECT_GT(returned, 250) << strategy_name(st) << " " << ndf_name(ndf);
    }
}

// int pdf d theta_o + P(no direction) = 1, the two integrals independent (over theta_o and over
// the facet angle), to their tolerances (1e-10 and 1e-11).
void check_normalization(NdfKind ndf, double alpha, double deg) {
  for (FacetStrategy st : kStrategies) {
    if (!strategy_supports(st, ndf, true)) continue;
    const double ti = deg * kRadPerDeg;
    const SamplerOptions opt{st, 64};
    const double integral =
        integrate_half_circle(
            ti, [&](double to) { return vgroove_pdf_flatland(ti, to, ndf, alpha, opt); }, alpha, 1e-10)
            .value;
    const double fail = sampler_failure_probability_flatland(ti, ndf, alpha, opt);
    EXPECT_NEAR(integral + fail, 1.0, 1e-9)
        << strategy_name(st) << " " << ndf_name(ndf) << " alpha=" << alpha << " theta_i=" << deg << " fail " << fail;
  }
}

TEST(SamplingFlatland, PdfIntegratesToOneMinusTheFailureProbability) {
  check_normalization(NdfKind::ggx, 0.5, 30.0);
  check_normalization(NdfKind::beckmann, 1.0, 85.0);
  check_normalization(NdfKind::phong, 1.5, 60.0);
}

// The grid (label long): every NDF, alpha 0.1..1.5, theta_i 0..85 deg, every strategy.
TEST(SamplingFlatlandLong, PdfIntegratesToOneMinusTheFailureProbability) {
  for (NdfKind ndf : kNdfs)
    for (double alpha : {0.1, 0.5, 1.0, 1.5})
      for (double deg : {0.0, 30.0, 60.0, 85.0}) check_normalization(ndf, alpha, deg);
}

// The printed p = |s.n| D2(s) G summed over the paths lacks the Jacobian 1/(2k): at small alpha it
// integrates to about 2 times the routine's mass (ERRATA E-IS1).
TEST(SamplingFlatland, PrintedPIsNotADensity) {
  for (double alpha : {0.1, 0.5})
    for (double deg : {0.0, 45.0}) {
      const double ti = deg * kRadPerDeg;
      const double printed =
          integrate_half_circle(
              ti, [&](double to) { return printed_p_flatland(ti, to, NdfKind::ggx, alpha, 64); }, alpha, 1e-9)
              .value;
      const double mass = 1.0 - sampler_failure_probability_flatland(ti, NdfKind::ggx, alpha,
                                                                     SamplerOptions{FacetStrategy::printed, 64});
      EXPECT_GT(printed / mass, 1.9) << "alpha=" << alpha << " theta_i=" << deg;
    }
}

TEST(SamplingFlatland, MeanWeightIsTheAlbedo) {
  const NdfKind ndf = NdfKind::beckmann;
  const double alpha = 0.8, ti = 40.0 * kRadPerDeg;
  const SamplerOptions base{FacetStrategy::vndf, 64};
  const double albedo =
      integrate_half_circle(
          ti, [&](double to) { return vgroove_pdf_and_brdf_flatland(ti, to, ndf, alpha, base).rho_cos; }, alpha, 1e-11)
          .value;
  for (FacetStrategy st : {FacetStrategy::printed, FacetStrategy::vndf}) {
    std::mt19937_64 g(61);
    const long n = 40000;
    double sum = 0.0, sum2 = 0.0;
    for (long s = 0; s < n; ++s) {
      const double w = sample_vgroove_flatland(ti, uniforms(g), ndf, alpha, SamplerOptions{st, 64}).weight;
      sum += w, sum2 += w * w;
    }
    // The V-cavity strategy's weights are 1 or 0 (paths beyond max_k, probability 1 - albedo =
    // 3e-12 here): its sample variance can be 0, so the standard error is at least the Bernoulli
    // one, sqrt(albedo (1 - albedo) / n); plus the quadrature's tolerance.
    const double mean = sum / n;
    const double se = std::max(std::sqrt((sum2 / n - mean * mean) / n), std::sqrt(albedo * (1.0 - albedo) / n));
    EXPECT_NEAR(mean, albedo, 5.0 * se + 1e-11) << strategy_name(st) << " se " << se;
  }
}

TEST(SamplingFlatland, HardCases) {
  const double top = 1.0 - std::ldexp(1.0, -53);
  int returned = 0;
  for (FacetStrategy st : kStrategies)
    for (NdfKind ndf : kNdfs) {
      if (!strategy_supports(st, ndf, true)) continue;
      for (double alpha : {0.01, 2.0})
        for (double deg : {0.0, 89.99, -89.99})
          for (int corner = 0; corner < 16; ++corner) {
            std::array<double, 4> u;
            for (int d = 0; d < 4; ++d) u[d] = (corner >> d) & 1 ? top : 0.0;
            const VgrooveSampleFlatland s =
                sample_vgroove_flatland(deg * kRadPerDeg, u, ndf, alpha, SamplerOptions{st});
            ASSERT_TRUE(std::isfinite(s.theta_o) && std::abs(s.theta_o) < 0.5 * std::numbers::pi);
            ASSERT_FALSE(std::isnan(s.pdf) || std::isnan(s.weight));
            if (s.k == 0) {
              EXPECT_EQ(s.pdf, 0.0);
              EXPECT_EQ(s.weight, 0.0);
            } else {
              EXPECT_TRUE(s.pdf > 0.0 && std::isfinite(s.pdf) && std::isfinite(s.weight) && s.weight >= 0.0)
                  << strategy_name(st) << " " << ndf_name(ndf) << " alpha=" << alpha << " theta_i=" << deg;
              ++returned;
            }
          }
    }
  EXPECT_GT(returned, 0);
}

// The default max_k loses fewer than one sample in 10^7 in flatland too (sampling_3d.h).
TEST(SamplingFlatland, DefaultMaxKLosesFewerThanOneSampleInTenMillion) {
  for (const FacetStrategy st : {FacetStrategy::vndf, FacetStrategy::printed}) {
    EXPECT_LT(sampler_beyond_max_k_probability_flatland(0.0, NdfKind::ggx, 2.0, SamplerOptions{st}), 1e-7);
    EXPECT_LT(sampler_beyond_max_k_probability_flatland(30.0 * kRadPerDeg, NdfKind::phong, 1.0, SamplerOptions{st}),
              1e-7);
    EXPECT_LT(sampler_beyond_max_k_probability_flatland(80.0 * kRadPerDeg, NdfKind::ggx, 1.0, SamplerOptions{st}),
              1e-7);
  }
}

}  // namespace
}  // namespace vgroove::analytic
