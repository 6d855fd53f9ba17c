// vgroove analytic: importance sampling of the flatland symmetric V-groove BRDF (brdf_flatland.h),
// the density of the exit angles it produces and the weight rho2 cos / pdf; F = 1. Lee et al.
// 2018 ("Practical Multiple Scattering for Rough Surfaces"), Sec. 6 written for flatland: the
// routine of sampling_3d.h in one dimension less, with the flatland Jacobian 1 / (2k):
//   pdf(theta_o) = sum_k sum_m q(theta_sm) P(k | theta_sm) / (2k),
// equal to rho2 cos(theta_o) for the V-cavity's visible normals. Zero-weight returns as in 3D;
// no flatland direction is singular.
// Tests: tests/analytic/sampling_flatland_test.cpp (SamplingFlatland.VcavityPdfIsTheBrdfTimesCosine,
// SamplingFlatland.PdfIntegratesToOneMinusTheFailureProbability, SamplingFlatland.WeightIsEvalCosOverPdf,
// SamplingFlatland.PrintedPIsNotADensity, SamplingFlatland.HardCases,
// SamplingFlatland.DefaultMaxKLosesFewerThanOneSampleInTenMillion), tests/analytic/sampling_chi2_test.cpp.
// Derivation: docs/derivations/sampling.md.
#pragma once

#include "vgroove/analytic/facet_strategy.h"
#include "vgroove/analytic/ndf.h"
#include "vgroove/analytic/sampling_3d.h"

#include <array>

namespace vgroove::analytic {

struct VgrooveSampleFlatland {
  double theta_o = 0.0;  // the exit angle (-theta_i on a zero-weight return)
  int k = 0;
  double pdf = 0.0;  // per radian
  double weight = 0.0;
  bool beyond_max_k = false;  // zero weight because the drawn path has more than max_k reflections
};

VgrooveSampleFlatland sample_vgroove_flatland(double theta_i, const std::array<double, 4>& u, NdfKind ndf, double alpha,
                                              const SamplerOptions& opt);

// pdf(theta_o) and rho2(theta_i, theta_o) cos(theta_o) (k <= max_k, F = 1) in one pass over the
// paths; the rho2 part is flatland_brdf's sum (brdf_flatland.h) visited in a single pass.
struct PdfAndBrdf2 {
  double pdf = 0.0;
  double rho_cos = 0.0;
};
PdfAndBrdf2 vgroove_pdf_and_brdf_flatland(double theta_i, double theta_o, NdfKind ndf, double alpha,
                                          const SamplerOptions& opt);
double vgroove_pdf_flatland(double theta_i, double theta_o, NdfKind ndf, double alpha, const SamplerOptions& opt);
double vgroove_pdf_flatland_k(double theta_i, double theta_o, NdfKind ndf, double alpha, const SamplerOptions& opt,
                              int k_lo, int k_hi);
// The printed p(theta_o) = |s.n| D2(s) G summed over the paths (not a density, ERRATA E-IS1).
double printed_p_flatland(double theta_i, double theta_o, NdfKind ndf, double alpha, int max_k);

// The probability of no direction, integrated over the facet angle (independent of pdf).
double sampler_failure_probability_flatland(double theta_i, NdfKind ndf, double alpha, const SamplerOptions& opt,
                                            double tol = 1e-11);
// Its part from the paths of more than max_k reflections (sampling_3d.h).
double sampler_beyond_max_k_probability_flatland(double theta_i, NdfKind ndf, double alpha, const SamplerOptions& opt,
                                                 double tol = 1e-11);

// The flatland cosine law: pdf = cos(theta_o) / 2 over (-pi/2, pi/2), theta_o = asin(2 u - 1).
double sample_cosine_flatland(double u);
double cosine_flatland_pdf(double theta_o);

}  // namespace vgroove::analytic
