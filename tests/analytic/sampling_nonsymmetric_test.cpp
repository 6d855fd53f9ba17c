// Tests of the nonsymmetric V-groove sampler (analytic/sampling_nonsymmetric.h): the pdf integrates
// to 1 minus the failure probability (two independent quadratures: over o, and over the facets and
// partners), the weight is eval cos / pdf, the mean weight is the albedo of Eq. 23 by quadrature
// within its standard error, and the hard cases stay finite. The chi-square tests are in
// tests/analytic/sampling_chi2_test.cpp.
#include "vgroove/analytic/sampling_nonsymmetric.h"

#include "vgroove/analytic/brdf_nonsymmetric.h"
#include "vgroove/analytic/hemisphere_quadrature.h"
#include "vgroove/analytic/kaleidoscope_nonsymmetric.h"
#include "vgroove/analytic/partner_distribution.h"
#include "vgroove/analytic/vndf.h"
#include "vgroove/common/angles.h"

#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <numbers>
#include <random>

namespace vgroove::analytic {
namespace {

std::array<double, 5> uniforms(std::mt19937_64& g) {
  std::uniform_real_distribution<double> U(0.0, 1.0);
  return {U(g), U(g), U(g), U(g), U(g)};
}

// The pdf's tolerance for the quadratures over o (the normalization asks 1e-6).
NonsymmetricSampler sampler(NdfKind ndf, double alpha, FacetStrategy st, bool flat, int max_k = 64) {
  NonsymmetricSampler S = make_nonsymmetric_sampler(ndf, alpha, SamplerOptions{st, max_k}, flat);
  S.tolerance = 1e-8;
  return S;
}

void check_normalization_flatland(NdfKind ndf, double alpha, double deg, FacetStrategy st) {
  const NonsymmetricSampler S = sampler(ndf, alpha, st, true);
  const double ti = deg * kRadPerDeg;
  const double mass = integrate_half_circle(
                          ti, [&](double to) { return nonsymmetric_pdf_flatland(S, ti, to); }, alpha, 1e-8)
                          .value;
  const double fail = nonsymmetric_failure_probability_flatland(S, ti);
  EXPECT_NEAR(mass + fail, 1.0, 2e-6) << ndf_name(ndf) << " " << alpha << " " << deg << " " << strategy_name(st)
                                      << ": mass " << mass << " fail " << fail;
}

// The printed strategy fails on shadowed and unlit draws (3 % here), the V-cavity VNDF only where
// the partner shadows the whole facet: both sum to 1 with the pdf's integral.
TEST(SamplingNonsymmetric, FlatlandPdfIntegratesToOneMinusTheFailureProbability) {
  check_normalization_flatland(NdfKind::ggx, 0.5, 30.0, FacetStrategy::vndf);
}

TEST(SamplingNonsymmetricLong, FlatlandPdfIntegratesToOneMinusTheFailureProbability) {
  check_normalization_flatland(NdfKind::ggx, 0.5, 30.0, FacetStrategy::printed);
  check_normalization_flatland(NdfKind::beckmann, 1.0, 75.0, FacetStrategy::vndf);
  check_normalization_flatland(NdfKind::phong, 0.7, 60.0, FacetStrategy::printed);
  check_normalization_flatland(NdfKind::ggx, 1.5, 85.0, FacetStrategy::smith_vndf);
}

TEST(SamplingNonsymmetricLong, ThreeDPdfIntegratesToOneMinusTheFailureProbability) {
  for (FacetStrategy st : {FacetStrategy::vndf, FacetStrategy::printed}) {
    const NonsymmetricSampler S = sampler(NdfKind::ggx, 0.5, st, false);
    const Dir3 i = dir3(30.0 * kRadPerDeg, std::numbers::pi);
    HemisphereOptions ho;
    ho.tol = 1e-5;
    ho.scale = 0.5;
    const double mass = integrate_hemisphere(
                            Dir3{-i.x, -i.y, i.z}, [&](const Dir3& o) { return nonsymmetric_pdf_3d(S, i, o); }, ho)
                            .value;
    const double fail = nonsymmetric_failure_probability_3d(S, i);
    EXPECT_NEAR(mass + fail, 1.0, 3e-5) << strategy_name(st) << ": mass " << mass << " fail " << fail;
  }
}

// The flatland pdf of k reflections at theta_o by another route: for every partner tilt B of a
// dense midpoint grid and every branch of Eq. (8), the first facet's tilt theta_l that sends
// theta_i to theta_o, its Eq. (9) share of k reflections, q(theta_l) P2(B) / |d theta_o / d theta_l|.
double brute_pdf_flatland_k(NdfKind ndf, double alpha, double ti, double to, int k, int nb) {
  constexpr double pi = std::numbers::pi;
  double sum = 0.0;
  for (double sgn : {1.0, -1.0}) {
    const double t = sgn * ti, tt = sgn * to;
    for (int j = 0; j < nb; ++j) {
      const double B = (j + 0.5) * (0.5 * pi) / nb;
      for (int m = -4; m <= 4; ++m) {
        // Eq. (8): even k, t_o = t_i + pi - k (pi + l - B); odd k, t_o = -t_i + (k + 1) l - (k - 1) B + (k - 1) pi.
        const double l = k % 2 == 0 ? (t + pi - k * pi + k * B - tt + 2.0 * pi * m) / k
                                    : (tt + t + (k - 1) * B - (k - 1) * pi + 2.0 * pi * m) / (k + 1);
        if (!(l <= 0.0 && l > -0.5 * pi)) continue;
        const NonsymmetricPrediction g = G_nonsymmetric(t, l, B, FacetSide::left);
        if (!g.lit) continue;
        double G = 0.0;
        for (const BounceShare& z : g.share)
          if (z.n == k) G += z.G;
        const double jac = k % 2 == 0 ? 1.0 / k : 1.0 / (k + 1);
        sum += projected_ndf2_pdf(ndf, alpha, sgn * l) * P2_theta_r(ndf, B, alpha) * G * jac * (0.5 * pi) / nb;
      }
    }
  }
  return sum;
}

// Light of k reflections can fill a small part of a B-piece only: here (k = 3, the mirrored
// facet first) 7 % of it, which a single 15-point rule over the piece never sampled (the pdf was
// 2.0 % low at theta_o = -28 deg, and its integral 8e-6 short of 1 - the failure probability).
TEST(SamplingNonsymmetric, FlatlandPdfFindsZonesNarrowerThanTheirPiece) {
  const NonsymmetricSampler S = sampler(NdfKind::ggx, 0.5, FacetStrategy::printed, true);
  const double ti = 30.0 * kRadPerDeg;
  for (double deg : {-28.0, -5.0, 15.0, 50.0}) {
    const double to = deg * kRadPerDeg;
    const double lib = nonsymmetric_pdf_flatland_k(S, ti, to, 3, 3);
    const double brute = brute_pdf_flatland_k(NdfKind::ggx, 0.5, ti, to, 3, 200000);
    EXPECT_NEAR(lib / brute, 1.0, 2e-5) << deg << " deg: " << lib << " vs " << brute;
  }
}

// sample() returns rho cos / pdf with rho = Eq. 23 (nonsymmetric_brdf) and pdf = the pdf function,
// at the o it returns: 1e-12 relative. The path's k is among the paths to o (pdf_k > 0).
TEST(SamplingNonsymmetric, WeightIsEvalCosOverPdf) {
  std::mt19937_64 g(61);
  for (FacetStrategy st : {FacetStrategy::printed, FacetStrategy::vndf}) {
    const NonsymmetricSampler S = sampler(NdfKind::ggx, 0.6, st, false, 16);
    const Dir3 i = dir3(40.0 * kRadPerDeg, 2.0);
    NonsymmetricModel m;
    m.roughness = isotropic_roughness(NdfKind::ggx, 0.6);
    m.tolerance = S.tolerance;
    int returned = 0;
    for (int n = 0; n < 12; ++n) {
      const VgrooveSample3d x = sample_nonsymmetric_3d(S, i, uniforms(g));
      if (x.k == 0) continue;
      ++returned;
      const double eval = nonsymmetric_brdf(i, x.o, 16, m) * x.o.z;
      const double pdf = nonsymmetric_pdf_3d(S, i, x.o);
      EXPECT_NEAR(x.weight, eval / pdf, 1e-12 * eval / pdf);
      EXPECT_EQ(x.pdf, pdf);
      EXPECT_GT(nonsymmetric_pdf_3d_k(S, i, x.o, x.k, x.k), 0.0);
    }
    EXPECT_GT(returned, 6);
  }
  const NonsymmetricSampler S = sampler(NdfKind::beckmann, 0.4, FacetStrategy::vndf, true, 16);
  NonsymmetricModel m;
  m.roughness = isotropic_roughness(NdfKind::beckmann, 0.4);
  m.tolerance = S.tolerance;
  for (int n = 0; n < 12; ++n) {
    const VgrooveSampleFlatland x = sample_nonsymmetric_flatland(S, -0.7, uniforms(g));
    if (x.k == 0) continue;
    const double eval = flatland_nonsymmetric_brdf(-0.7, x.theta_o, 16, m) * std::cos(x.theta_o);
    const double pdf = nonsymmetric_pdf_flatland(S, -0.7, x.theta_o);
    EXPECT_NEAR(x.weight, eval / pdf, 1e-12 * eval / pdf);
    EXPECT_GT(nonsymmetric_pdf_flatland_k(S, -0.7, x.theta_o, x.k, x.k), 0.0);
  }
}

// The mean weight over N samples is the albedo int rho cos d theta_o (quadrature, independent of
// the sampler) within 5 standard errors (plus the table's bias, < 1e-5).
TEST(SamplingNonsymmetric, MeanWeightIsTheAlbedo) {
  const double ti = 50.0 * kRadPerDeg;
  for (FacetStrategy st : {FacetStrategy::printed, FacetStrategy::vndf}) {
    NonsymmetricSampler S = sampler(NdfKind::ggx, 0.5, st, true, 16);
    S.tolerance = 1e-7;
    NonsymmetricModel m;
    m.roughness = isotropic_roughness(NdfKind::ggx, 0.5);
    m.tolerance = 1e-8;
    const double albedo =
        integrate_half_circle(
            ti, [&](double to) { return flatland_nonsymmetric_brdf(ti, to, 16, m) * std::cos(to); }, 0.5, 1e-7)
            .value;
    std::mt19937_64 g(62);
    const int n = 600;
    double sum = 0.0, sum2 = 0.0;
    for (int j = 0; j < n; ++j) {
      const double w = sample_nonsymmetric_flatland(S, ti, uniforms(g)).weight;
      sum += w;
      sum2 += w * w;
    }
    const double mean = sum / n, var = std::max(0.0, sum2 / n - mean * mean) * n / (n - 1.0);
    const double se = std::sqrt(var / n);
    EXPECT_NEAR(mean, albedo, 5.0 * se + 1e-5) << strategy_name(st) << " albedo " << albedo << " se " << se;
    // The furnace: with F = 1 the albedo is 1 up to the paths beyond max_k.
    EXPECT_NEAR(albedo, 1.0, 1e-3);
  }
}

// The white furnace of Eq. 23 (flatland, F = 1): every ray that enters a groove leaves it, so the
// albedo of the pointwise BRDF, by deterministic quadrature over theta_o (independent of the
// sampler), is 1 up to the light beyond max_k and the quadrature's tolerance. The same BRDF with
// the Jacobian off by (k + 1)/k for k >= 2 (a deliberately broken variant) fails it.
TEST(SamplingNonsymmetric, FurnaceOfEq23Flatland) {
  struct Case {
    NdfKind ndf;
    double alpha, deg;
  };
  for (const Case& c : {Case{NdfKind::ggx, 0.5, 30.0}, Case{NdfKind::beckmann, 1.0, 70.0}}) {
    NonsymmetricModel m;
    m.roughness = isotropic_roughness(c.ndf, c.alpha);
    m.tolerance = 1e-9;
    const double ti = c.deg * kRadPerDeg;
    const int max_k = 64;
    auto albedo = [&](bool broken) {
      return integrate_half_circle(
                 ti,
                 [&](double to) {
                   double rho = 0.0;
                   for (int k = 1; k <= max_k; ++k)
                     rho += flatland_nonsymmetric_brdf_k(ti, to, k, m) * (broken && k >= 2 ? k / (k + 1.0) : 1.0);
                   return rho * std::cos(to);
                 },
                 c.alpha, 1e-8)
          .value;
    };
    const double a = albedo(false), b = albedo(true);
    std::printf("%s alpha %g theta_i %g: albedo %.10f, broken Jacobian %.6f\n", ndf_name(c.ndf), c.alpha, c.deg, a, b);
    EXPECT_NEAR(a, 1.0, 1e-6) << ndf_name(c.ndf);
    EXPECT_GT(std::abs(b - 1.0), 1e-3) << ndf_name(c.ndf);
  }
}

// u at 0 and 1 - 2^-53, theta_i at 0 and 89.99 deg, alpha 0.01 and 2: a finite o with a finite
// positive pdf, or the documented zero-weight return; never NaN.
TEST(SamplingNonsymmetric, HardCases) {
  const double top = 1.0 - std::ldexp(1.0, -53);
  for (NdfKind ndf : {NdfKind::beckmann, NdfKind::ggx, NdfKind::phong})
    for (double alpha : {0.01, 2.0}) {
      if (ndf == NdfKind::phong && alpha > 1.0) {
        EXPECT_THROW(make_nonsymmetric_sampler(ndf, alpha, SamplerOptions{}, false), std::domain_error);
        continue;
      }
      for (bool flat : {false, true}) {
        const NonsymmetricSampler S = sampler(ndf, alpha, FacetStrategy::vndf, flat, 16);
        for (double deg : {0.0, 89.99})
          for (double u : {0.0, top, 0.5}) {
            const std::array<double, 5> us{u, u, u, u, u};
            if (flat) {
              const VgrooveSampleFlatland x = sample_nonsymmetric_flatland(S, deg * kRadPerDeg, us);
              EXPECT_TRUE(std::isfinite(x.theta_o) && std::isfinite(x.pdf) && std::isfinite(x.weight));
              EXPECT_TRUE(x.k == 0 ? x.pdf == 0.0 && x.weight == 0.0 : x.pdf > 0.0) << alpha << " " << deg << " " << u;
            } else {
              const VgrooveSample3d x = sample_nonsymmetric_3d(S, dir3(deg * kRadPerDeg, 1.0), us);
              EXPECT_TRUE(std::isfinite(x.o.x) && std::isfinite(x.o.y) && std::isfinite(x.o.z));
              EXPECT_TRUE(std::isfinite(x.pdf) && std::isfinite(x.weight));
              EXPECT_TRUE(x.k == 0 ? x.pdf == 0.0 && x.weight == 0.0 : x.pdf > 0.0) << alpha << " " << deg << " " << u;
            }
          }
      }
    }
}

}  // namespace
}  // namespace vgroove::analytic
