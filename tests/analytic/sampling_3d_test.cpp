// Tests of the 3D V-groove sampler (analytic/sampling_3d.h): the V-cavity strategy's pdf is the
// BRDF, the weight is eval cos / pdf, every sampled path is one the pdf sums, the pdf integrates
// to 1 minus the failure probability (two independent quadratures), the mean weight is the albedo,
// the printed p(o) is not a density, and the hard cases stay finite. The sampler against its pdf:
// tests/analytic/sampling_chi2_test.cpp.
#include "vgroove/analytic/sampling_3d.h"

#include "vgroove/analytic/hemisphere_quadrature.h"
#include "vgroove/common/angles.h"

#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <limits>
#include <numbers>
#include <random>

namespace vgroove::analytic {
namespace {

constexpr NdfKind kNdfs[] = {NdfKind::beckmann, NdfKind::ggx, NdfKind::phong};
constexpr FacetStrategy kStrategies[] = {FacetStrategy::printed, FacetStrategy::vndf, FacetStrategy::smith_vndf,
                                         FacetStrategy::bounded_vndf};

// Schlick with F0 = 0.5: a conductor-like Fresnel plug-in.
double schlick(double c) { return 0.5 + 0.5 * std::pow(1.0 - std::clamp(c, 0.0, 1.0), 5.0); }

std::array<double, 4> uniforms(std::mt19937_64& g) {
  std::uniform_real_distribution<double> U(0.0, 1.0);
  return {U(g), U(g), U(g), U(g)};
}

// For the V-cavity's visible normals q(s) P(k | s) = D(s) |i.s| G / <i.n>, so the density of o is
// rho(i, o) cos(theta_o) with F = 1 (sampling_3d.h). Checked against vgroove_brdf, which sums the
// same paths by brdf_3d.cpp's own term.
TEST(Sampling3d, VcavityPdfIsTheBrdfTimesCosine) {
  std::mt19937_64 g(11);
  std::uniform_real_distribution<double> U(0.0, 1.0);
  for (int trial = 0; trial < 3000; ++trial) {
    const NdfKind ndf = kNdfs[trial % 3];
    const double alpha = 0.05 + 1.5 * U(g);
    const Dir3 i = dir3(std::acos(U(g)), 2.0 * std::numbers::pi * U(g));
    const Dir3 o = dir3(std::acos(U(g)), 2.0 * std::numbers::pi * U(g));
    const SamplerOptions opt{FacetStrategy::vndf, 64};
    const double pdf = vgroove_pdf_3d(i, o, ndf, alpha, opt);
    const double rho_cos = vgroove_brdf(i, o, ndf, alpha, opt.max_k) * o.z;
    EXPECT_NEAR(pdf, rho_cos, 1e-12 * rho_cos) << ndf_name(ndf) << " alpha=" << alpha << " trial " << trial;
  }
}

// The weight sample() returns is rho cos / pdf, with rho = vgroove_brdf (F included) and pdf =
// vgroove_pdf_3d evaluated afresh at the returned o: to 1e-12 relative, every strategy.
TEST(Sampling3d, WeightIsEvalCosOverPdf) {
  std::mt19937_64 g(12);
  std::uniform_real_distribution<double> U(0.0, 1.0);
  for (FacetStrategy st : kStrategies)
    for (NdfKind ndf : kNdfs) {
      if (!strategy_supports(st, ndf, false)) continue;
      int returned = 0;
      for (int trial = 0; trial < 400; ++trial) {
        const double alpha = 0.05 + 1.5 * U(g);
        const Dir3 i = dir3(0.5 * std::numbers::pi * U(g), 2.0 * std::numbers::pi * U(g));
        const SamplerOptions opt{st, 64};
        const FresnelFn F = trial % 2 == 0 ? FresnelFn{} : FresnelFn{schlick};
        const VgrooveSample3d s = sample_vgroove_3d(i, uniforms(g), ndf, alpha, opt, F);
        if (s.k == 0) continue;
        ++returned;
        const double pdf = vgroove_pdf_3d(i, s.o, ndf, alpha, opt);
        const double eval = vgroove_brdf(i, s.o, ndf, alpha, opt.max_k, F);
        EXPECT_NEAR(s.pdf, pdf, 1e-12 * pdf) << strategy_name(st) << " " << ndf_name(ndf) << " trial " << trial;
        EXPECT_NEAR(s.weight, eval * s.o.z / pdf, 1e-12 * s.weight)
            << strategy_name(st) << " " << ndf_name(ndf) << " alpha=" << alpha << " trial " << trial;
        // With F = 1 the V-cavity strategy samples the BRDF exactly.
        if (st == FacetStrategy::vndf && !F) {
          EXPECT_NEAR(s.weight, 1.0, 1e-12);
        }
      }
      EXPECT_GT(returned, 200) << strategy_name(st) << " " << ndf_name(ndf);
    }
}

// The path the routine drew is one of the paths the pdf sums: its k-part of the pdf is positive at
// the returned o, and the direction is a unit vector above the horizon.
TEST(Sampling3d, SampledPathIsAmongThePdfsPaths) {
  std::mt19937_64 g(13);
  std::uniform_real_distribution<double> U(0.0, 1.0);
  for (FacetStrategy st : kStrategies)
    for (int trial = 0; trial < 1500; ++trial) {
      const NdfKind ndf = st == FacetStrategy::smith_vndf || st == FacetStrategy::bounded_vndf ? NdfKind{NdfKind::ggx}
                                                                                               : kNdfs[trial % 3];
      const double alpha = 0.05 + 1.5 * U(g);
      const Dir3 i = dir3(0.5 * std::numbers::pi * U(g), 2.0 * std::numbers::pi * U(g));
      const SamplerOptions opt{st, 64};
      const VgrooveSample3d s = sample_vgroove_3d(i, uniforms(g), ndf, alpha, opt);
      if (s.k == 0) continue;
      EXPECT_NEAR(s.o.x * s.o.x + s.o.y * s.o.y + s.o.z * s.o.z, 1.0, 1e-14);
      EXPECT_GT(s.o.z, 0.0);
      EXPECT_GT(vgroove_pdf_3d_k(i, s.o, ndf, alpha, opt, s.k, s.k), 0.0)
          << strategy_name(st) << " " << ndf_name(ndf) << " alpha=" << alpha << " k=" << s.k << " trial " << trial;
    }
}

// The pdf's normalization by two independent quadratures: over o (Eq. 13's Jacobian and the
// inverted Eq. 5 inside the pdf) and over the facets (the routine's forward steps only):
// int pdf do + P(no direction) = 1. Tolerances: the two quadratures' (1e-6 and 1e-9). The
// chi-square tests repeat it for every case of their grid (the sum of the cells' integrals).
void check_normalization(NdfKind ndf, double alpha, double deg) {
  for (FacetStrategy st : kStrategies) {
    if (!strategy_supports(st, ndf, false)) continue;
    const Dir3 i = dir3(deg * kRadPerDeg, std::numbers::pi);
    const SamplerOptions opt{st, 64};
    HemisphereOptions ho;
    ho.tol = 1e-6;
    ho.scale = alpha;
    const AdaptiveResult r = integrate_hemisphere(
        Dir3{-i.x, -i.y, i.z}, [&](const Dir3& o) { return vgroove_pdf_3d(i, o, ndf, alpha, opt); }, ho);
    const double fail = sampler_failure_probability_3d(i, ndf, alpha, opt, 1e-9);
    EXPECT_NEAR(r.value + fail, 1.0, 2e-6) << strategy_name(st) << " " << ndf_name(ndf) << " alpha=" << alpha
                                           << " theta_i=" << deg << " (fail " << fail << ")";
  }
}

TEST(Sampling3d, PdfIntegratesToOneMinusTheFailureProbability) { check_normalization(NdfKind::ggx, 0.5, 30.0); }

TEST(Sampling3dLong, PdfIntegratesToOneMinusTheFailureProbability) {
  check_normalization(NdfKind::beckmann, 1.0, 70.0);
  check_normalization(NdfKind::phong, 0.3, 0.0);
  check_normalization(NdfKind::ggx, 1.5, 85.0);
}

// Lee et al. 2018, Sec. 6 prints p(o) = |s.n| D(s) G(i, o, s). Summed over the paths to o it is the
// density of the facet per d s, not of o per d o: without |ds/do| (Eq. 13; 1/(4 cos theta_d) for
// k = 1) it integrates to about 4 cos(theta_d) times the routine's mass, not to the mass
// (ERRATA E-IS1). The density of what the printed routine produces is vgroove_pdf_3d.
TEST(Sampling3d, PrintedPIsNotADensity) {
  const NdfKind ndf = NdfKind::ggx;
  const double alpha = 0.5;
  for (double deg : {0.0, 45.0}) {
    const Dir3 i = dir3(deg * kRadPerDeg, std::numbers::pi);
    HemisphereOptions ho;
    ho.tol = 1e-4;
    ho.scale = alpha;
    const double printed =
        integrate_hemisphere(
            Dir3{-i.x, -i.y, i.z}, [&](const Dir3& o) { return printed_p_3d(i, o, ndf, alpha, 64); }, ho)
            .value;
    const double mass = 1.0 - sampler_failure_probability_3d(i, ndf, alpha, SamplerOptions{FacetStrategy::printed, 64});
    EXPECT_GT(printed / mass, 2.5) << "theta_i=" << deg;  // 3.19 at normal incidence, 2.89 at 45 deg
  }
}

// The mean weight is the albedo of Eq. 17 (N = max_k): the estimator and the quadrature of
// vgroove_brdf cos over the hemisphere agree within 5 standard errors plus the quadrature's
// tolerance. (The white furnace holds both to 1: validation/furnace_suite.)
TEST(Sampling3d, MeanWeightIsTheAlbedo) {
  const NdfKind ndf = NdfKind::ggx;
  const double alpha = 0.7, deg = 50.0;
  const Dir3 i = dir3(deg * kRadPerDeg, std::numbers::pi);
  const SamplerOptions base{FacetStrategy::vndf, 64};
  HemisphereOptions ho;
  ho.tol = 1e-5;
  ho.scale = alpha;
  const FresnelFn F{schlick};
  const double albedo =
      integrate_hemisphere(
          Dir3{-i.x, -i.y, i.z}, [&](const Dir3& o) { return vgroove_brdf(i, o, ndf, alpha, 64, F) * o.z; }, ho)
          .value;
  for (FacetStrategy st : kStrategies) {
    std::mt19937_64 g(21);
    const long n = 20000;
    double sum = 0.0, sum2 = 0.0;
    for (long s = 0; s < n; ++s) {
      const double w = sample_vgroove_3d(i, uniforms(g), ndf, alpha, SamplerOptions{st, base.max_k}, F).weight;
      sum += w, sum2 += w * w;
    }
    const double mean = sum / n, se = std::sqrt((sum2 / n - mean * mean) / n);
    EXPECT_NEAR(mean, albedo, 5.0 * se + 2e-5) << strategy_name(st) << " se " << se;
  }
}

// Hard cases: u at 0 and 1 - 2^-53 in every coordinate, theta_i at 0 and 89.99 deg, alpha 0.01 and
// 2, every NDF and strategy: o finite and a unit vector, pdf finite and > 0 with a finite weight,
// or the documented zero-weight return (k = 0, pdf = 0, weight = 0). Never NaN.
TEST(Sampling3d, HardCases) {
  const double top = 1.0 - std::ldexp(1.0, -53);
  std::mt19937_64 g(31);
  std::uniform_real_distribution<double> U(0.0, 1.0);
  int returned = 0, zero = 0;
  for (FacetStrategy st : kStrategies)
    for (NdfKind ndf : kNdfs) {
      if (!strategy_supports(st, ndf, false)) continue;
      for (double alpha : {0.01, 2.0})
        for (double deg : {0.0, 89.99})
          for (int corner = 0; corner < 16 + 64; ++corner) {
            std::array<double, 4> u;
            for (int d = 0; d < 4; ++d)  // the 16 corners, then corners mixed with random values
              u[d] =
                  corner < 16 ? ((corner >> d) & 1 ? top : 0.0) : ((corner >> d) & 1 ? (U(g) < 0.5 ? top : 0.0) : U(g));
            const Dir3 i = dir3(deg * kRadPerDeg, 0.3);
            const VgrooveSample3d s = sample_vgroove_3d(i, u, ndf, alpha, SamplerOptions{st, 256}, FresnelFn{schlick});
            ASSERT_TRUE(std::isfinite(s.o.x) && std::isfinite(s.o.y) && std::isfinite(s.o.z))
                << strategy_name(st) << " " << ndf_name(ndf) << " alpha=" << alpha << " theta_i=" << deg;
            EXPECT_NEAR(s.o.x * s.o.x + s.o.y * s.o.y + s.o.z * s.o.z, 1.0, 1e-12);
            ASSERT_FALSE(std::isnan(s.pdf) || std::isnan(s.weight));
            if (s.k == 0) {
              EXPECT_EQ(s.pdf, 0.0);
              EXPECT_EQ(s.weight, 0.0);
              ++zero;
            } else {
              EXPECT_TRUE(s.pdf > 0.0 && std::isfinite(s.pdf)) << strategy_name(st) << " " << ndf_name(ndf);
              EXPECT_TRUE(s.weight >= 0.0 && std::isfinite(s.weight));
              EXPECT_GT(s.o.z, 0.0);
              ++returned;
            }
          }
    }
  EXPECT_GT(returned, 0);
  EXPECT_GT(zero, 0);
  // The pdf itself at hard directions: finite or +inf exactly at the mirror direction, never NaN.
  for (NdfKind ndf : kNdfs)
    for (double alpha : {0.01, 2.0})
      for (double deg : {0.0, 89.99}) {
        const Dir3 i = dir3(deg * kRadPerDeg, 0.0);
        for (const Dir3& o : {Dir3{-i.x, -i.y, i.z}, i, dir3(89.99 * kRadPerDeg, 1.0), Dir3{0.0, 0.0, 1.0}}) {
          const double p = vgroove_pdf_3d(i, o, ndf, alpha, SamplerOptions{});
          EXPECT_FALSE(std::isnan(p)) << ndf_name(ndf) << " alpha=" << alpha << " theta_i=" << deg;
          EXPECT_GE(p, 0.0);
        }
      }
}

TEST(Sampling3d, CosineHemisphere) {
  std::mt19937_64 g(41);
  std::uniform_real_distribution<double> U(0.0, 1.0);
  double mean_z = 0.0;
  const int n = 100000;
  for (int s = 0; s < n; ++s) mean_z += sample_cosine_hemisphere(U(g), U(g)).z / n;
  // E[cos] under cos/pi is 2/3, variance 1/2 - 4/9 = 1/18.
  EXPECT_NEAR(mean_z, 2.0 / 3.0, 5.0 * std::sqrt(1.0 / 18.0 / n));
  EXPECT_NEAR(cosine_hemisphere_pdf(Dir3{0.0, 0.0, 1.0}), 1.0 / std::numbers::pi, 1e-16);
}

}  // namespace
}  // namespace vgroove::analytic

namespace vgroove::analytic {
namespace {

// The default max_k (kSamplerMaxK) loses fewer than one sample in 10^7 (sampling_3d.h): at the
// heaviest tails among GGX, Beckmann and Phong up to alpha 1, the share beyond max_k (integrated
// over the facets) is below 1e-7. At max_k 256 it is 1.5e-4 for GGX alpha 2.
TEST(Sampling3d, DefaultMaxKLosesFewerThanOneSampleInTenMillion) {
  struct Case {
    NdfKind ndf;
    double alpha, deg;
  };
  for (const Case c :
       {Case{NdfKind::ggx, 2.0, 0.0}, Case{NdfKind::beckmann, 2.0, 60.0}, Case{NdfKind::phong, 1.0, 30.0}}) {
    const Dir3 i = dir3(c.deg * kRadPerDeg, std::numbers::pi);
    for (FacetStrategy st : {FacetStrategy::vndf, FacetStrategy::printed}) {
      const double lost = sampler_beyond_max_k_probability_3d(i, c.ndf, c.alpha, SamplerOptions{st}, 1e-10);
      EXPECT_LT(lost, 1e-7) << ndf_name(c.ndf) << " alpha " << c.alpha << " " << strategy_name(st);
      EXPECT_GE(lost, 0.0);
    }
  }
}

// A sample lost to max_k says so, and the share of them is the integral over the facets: with
// max_k = 4 at GGX alpha 1, 30 deg, N = 200000 samples, the count is binomial (N, p) and must lie
// within 4.5 sigma of N p. With the vndf strategy the paths beyond max_k are all its failures;
// the printed one also fails on shadowed facets, which are not counted.
TEST(Sampling3d, SamplesLostBeyondMaxKAreCountedAtTheirShare) {
  const Dir3 i = dir3(30.0 * kRadPerDeg, std::numbers::pi);
  for (FacetStrategy st : {FacetStrategy::vndf, FacetStrategy::printed}) {
    const SamplerOptions opt{st, 4};
    const double p = sampler_beyond_max_k_probability_3d(i, NdfKind::ggx, 1.0, opt, 1e-10);
    const double fail = sampler_failure_probability_3d(i, NdfKind::ggx, 1.0, opt, 1e-10);
    ASSERT_GT(p, 1e-3);
    if (st == FacetStrategy::vndf) {
      EXPECT_NEAR(p, fail, 1e-9);
    } else {
      EXPECT_LT(p, fail - 0.01);
    }
    std::mt19937_64 g(7);
    const long N = 200000;
    long lost = 0, none = 0;
    for (long n = 0; n < N; ++n) {
      const VgrooveSample3d s = sample_vgroove_3d(i, uniforms(g), NdfKind::ggx, 1.0, opt);
      if (s.k == 0) ++none;
      if (!s.beyond_max_k) continue;
      ++lost;
      EXPECT_EQ(s.k, 0);
      EXPECT_EQ(s.weight, 0.0);
    }
    const double mean = N * p, sigma = std::sqrt(N * p * (1.0 - p));
    EXPECT_NEAR(static_cast<double>(lost), mean, 4.5 * sigma) << strategy_name(st) << " p " << p;
    if (st == FacetStrategy::printed) {
      EXPECT_GT(none, lost + 1000);
    }
  }
}

// The pdf's sum stops at the aperture below which D is exactly 0 (ndf.h, D_vanishing_aperture):
// near the retro direction, where paths of thousands of reflections end, it still equals the BRDF
// times the cosine (vgroove_brdf sums every aperture).
TEST(Sampling3d, PdfStopsOnlyWhereDVanishes) {
  const Dir3 i = dir3(60.0 * kRadPerDeg, std::numbers::pi);
  for (const NdfKind ndf : {NdfKind::beckmann, NdfKind::phong})
    for (const double alpha : {0.05, 0.5, 2.0}) {
      if (ndf == NdfKind::phong && alpha > 1.0) continue;
      for (const double d : {1e-2, 1e-3, 1e-4}) {
        const Dir3 o = dir3((60.0 - d) * kRadPerDeg, std::numbers::pi + 3.0 * d * kRadPerDeg);  // near i
        const double pdf = vgroove_pdf_3d(i, o, ndf, alpha, SamplerOptions{});
        const double rho_cos = vgroove_brdf(i, o, ndf, alpha, kSamplerMaxK) * o.z;
        EXPECT_NEAR(pdf, rho_cos, 1e-12 * std::max(1.0, rho_cos)) << ndf_name(ndf) << " alpha " << alpha << " d " << d;
      }
    }
}

}  // namespace
}  // namespace vgroove::analytic
