// vgroove analytic: importance sampling of the 3D symmetric V-groove BRDF (Lee et al. 2018,
// "Practical Multiple Scattering for Rough Surfaces", Sec. 6, Eq. (4)-(6), (13), (16)-(17)), the
// exact density of the directions it produces (the sum over every path ending at o with the
// Jacobian of Eq. 13) and the weight rho cos / pdf. The facet's law is a choice (facet_strategy.h);
// with the V-cavity's visible normals the pdf equals rho cos with F = 1. The printed p(o) is not a
// density (ERRATA E-IS1). Paths beyond max_k are the reported failure share; the default
// kSamplerMaxK = 16384 keeps it below 1e-7 for GGX and Beckmann at alpha in [0.01, 2].
// Holds: pdf integrates to 1 - failure probability; the weight is rho cos / pdf; every returned o
// and pdf is finite, or the documented zero-weight return.
// Tests: tests/analytic/sampling_3d_test.cpp (Sampling3d.VcavityPdfIsTheBrdfTimesCosine,
// Sampling3d.PdfIntegratesToOneMinusTheFailureProbability, Sampling3d.WeightIsEvalCosOverPdf,
// Sampling3d.DefaultMaxKLosesFewerThanOneSampleInTenMillion, Sampling3d.HardCases),
// tests/analytic/sampling_chi2_test.cpp. Timings: docs/performance.md.
// Derivation: docs/derivations/sampling.md.
#pragma once

#include "vgroove/analytic/brdf_3d.h"
#include "vgroove/analytic/facet_strategy.h"

#include <array>

namespace vgroove::analytic {

// The default max_k of the symmetric samplers (header), on every face: SamplerOptions, the
// validation's Chi2Spec and VarianceSpec, `vgroove sample --max-k`, Python's sample and pdf.
inline constexpr int kSamplerMaxK = 16384;

struct SamplerOptions {
  FacetStrategy strategy = FacetStrategy::vndf;
  int max_k = kSamplerMaxK;  // paths with more reflections return zero weight (header)
};

struct VgrooveSample3d {
  Dir3 o;                     // the exit direction (the mirror direction of i on a zero-weight return)
  int k = 0;                  // reflections of the sampled path; 0 on a zero-weight return
  double pdf = 0.0;           // density of o per steradian, every path with k <= max_k
  double weight = 0.0;        // rho(i, o) cos(theta_o) / pdf, Fresnel included
  bool beyond_max_k = false;  // zero weight because the drawn path has more than max_k reflections
};

// The routine of the header: u = (u0, u1, u2, u3) in [0, 1)^4.
VgrooveSample3d sample_vgroove_3d(const Dir3& i, const std::array<double, 4>& u, NdfKind ndf, double alpha,
                                  const SamplerOptions& opt, const FresnelFn& F = {});

// The density of o (the header's sum; 0 below the horizon, +inf at h = n exactly).
double vgroove_pdf_3d(const Dir3& i, const Dir3& o, NdfKind ndf, double alpha, const SamplerOptions& opt);
// The part of it from paths with k in [k_lo, k_hi].
double vgroove_pdf_3d_k(const Dir3& i, const Dir3& o, NdfKind ndf, double alpha, const SamplerOptions& opt, int k_lo,
                        int k_hi);

// pdf(o) and rho(i, o) cos(theta_o) (Eq. 17 with N = max_k) in one pass over the paths: what
// sample_vgroove_3d computes at the o it returns.
struct PdfAndBrdf {
  double pdf = 0.0;
  double rho_cos = 0.0;
};
PdfAndBrdf vgroove_pdf_and_brdf_3d(const Dir3& i, const Dir3& o, NdfKind ndf, double alpha, const SamplerOptions& opt,
                                   const FresnelFn& F = {});

// The printed p(o) = |s.n| D(s) G(i, o, s) (Lee et al. 2018, Sec. 6), summed over the paths that
// end at o (k <= max_k): not a density (ERRATA E-IS1), kept to show it.
double printed_p_3d(const Dir3& i, const Dir3& o, NdfKind ndf, double alpha, int max_k);

// The probability that sample_vgroove_3d returns no direction, integrated over the facets (not
// over o, so that it checks pdf's normalization independently): int q(s) P(no direction | s) ds
// by adaptive Gauss-Kronrod over (theta_s, phi_s) to about `tol`.
double sampler_failure_probability_3d(const Dir3& i, NdfKind ndf, double alpha, const SamplerOptions& opt,
                                      double tol = 1e-9);
// Its part from the paths of more than max_k reflections: the share of samples lost to max_k (with
// every strategy but the printed one, all of the failure probability).
double sampler_beyond_max_k_probability_3d(const Dir3& i, NdfKind ndf, double alpha, const SamplerOptions& opt,
                                           double tol = 1e-9);

// Cosine-weighted hemisphere sampling, the baseline: pdf = cos(theta_o) / pi.
Dir3 sample_cosine_hemisphere(double u0, double u1);
double cosine_hemisphere_pdf(const Dir3& o);

}  // namespace vgroove::analytic
