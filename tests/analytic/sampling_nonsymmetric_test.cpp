// Tests of the nonsymmetric V-groove sampler (analytic/sampling_nonsymmetric.h): the pdf integrates
// to 1 minus the failure probability (two independent quadratures, over o and over the facets and
// partners), the weight is eval cos / pdf, the mean weight is the albedo of Eq. 23 by quadrature
// within its standard error, and the hard cases stay finite.
#include "vgroove/analytic/sampling_nonsymmetric.h"

#include "vgroove/analytic/brdf_nonsymmetric.h"
#include "vgroove/analytic/hemisphere_quadrature.h"
#include "vgroove/common/angles.h"

#include <gtest/gtest.h>

#include <array>
#include <chrono>
#include <cmath>
#include <numbers>
#include <random>

namespace vgroove::analytic {
namespace {

std::array<double, 5> uniforms(std::mt19937_64& g) {
  std::uniform_real_distribution<double> U(0.0, 1.0);
  return {U(g), U(g), U(g), U(g), U(g)};
}

void check_normalization_flatland(NdfKind ndf, double alpha, double deg, FacetStrategy st) {
  const NonsymmetricSampler S = make_nonsymmetric_sampler(ndf, alpha, SamplerOptions{st, 64}, true);
  const double ti = deg * kRadPerDeg;
  auto t0 = std::chrono::steady_clock::now();
  const double mass =
      integrate_half_circle(ti, [&](double to) { return nonsymmetric_pdf_flatland(S, ti, to); }, alpha, 1e-9).value;
  auto t1 = std::chrono::steady_clock::now();
  const double fail = nonsymmetric_failure_probability_flatland(S, ti);
  std::printf("mass %.10f fail %.10f %.2fs %.2fs\n", mass, fail, std::chrono::duration<double>(t1 - t0).count(), std::chrono::duration<double>(std::chrono::steady_clock::now() - t1).count());
  EXPECT_NEAR(mass + fail, 1.0, 1e-6) << ndf_name(ndf) << " " << alpha << " " << deg << " " << strategy_name(st)
                                      << ": mass " << mass << " fail " << fail;
}

TEST(SamplingNonsymmetric, FlatlandPdfIntegratesToOneMinusTheFailureProbability) {
  auto t0 = std::chrono::steady_clock::now();
  check_normalization_flatland(NdfKind::ggx, 0.5, 30.0, FacetStrategy::vndf);
  std::printf("%.2fs\n", std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count());
  check_normalization_flatland(NdfKind::ggx, 0.5, 30.0, FacetStrategy::printed);
  check_normalization_flatland(NdfKind::beckmann, 1.0, 75.0, FacetStrategy::vndf);
}

TEST(SamplingNonsymmetric, ThreeDPdfIntegratesToOneMinusTheFailureProbability) {
  const NonsymmetricSampler S = make_nonsymmetric_sampler(NdfKind::ggx, 0.5, SamplerOptions{FacetStrategy::vndf, 64}, false);
  const Dir3 i = dir3(30.0 * kRadPerDeg, std::numbers::pi);
  HemisphereOptions ho;
  ho.tol = 1e-5;
  ho.scale = 0.5;
  auto t0 = std::chrono::steady_clock::now();
  const double mass = integrate_hemisphere(Dir3{-i.x, -i.y, i.z}, [&](const Dir3& o) { return nonsymmetric_pdf_3d(S, i, o); }, ho).value;
  auto t1 = std::chrono::steady_clock::now();
  const double fail = nonsymmetric_failure_probability_3d(S, i);
  auto t2 = std::chrono::steady_clock::now();
  EXPECT_NEAR(mass + fail, 1.0, 1e-4) << mass << " " << fail;
  std::printf("mass %.9f fail %.9f  %.2fs %.2fs\n", mass, fail, std::chrono::duration<double>(t1 - t0).count(), std::chrono::duration<double>(t2 - t1).count());
}

}  // namespace
}  // namespace vgroove::analytic
