// vgroove analytic: importance sampling of the 3D symmetric V-groove BRDF (Eq. 14-17), the
// density of the directions it produces, and the weight rho cos / pdf.
//
// Lee, Jarabo, Jeon, Gutierrez, Kim. "Practical Multiple Scattering for Rough Surfaces".
// ACM TOG 37(6), 2018. Sec. 6 (importance sampling), Eq. (4)-(6), (13), (16)-(17).
//
// The routine (Sec. 6, with the facet's distribution a choice, facet_strategy.h):
//   1. draw a facet s (u0, u1, u2) from the strategy's density q(s) over the hemisphere of normals;
//      s is the left facet of the groove whose cross-section is spanned by a = the horizontal
//      direction of s and n (brdf_3d.h), aperture theta_v = pi - 2 theta_s;
//   2. in that cross-section the light arrives at t_i = atan2(-(i.a), i.n) (ERRATA E3D); Eq. (4)
//      gives K and Eq. (6) (corrected, ERRATA E1) splits the rays aimed at s into the K - 1
//      reflections (width f_a - f_K), the K reflections (f_K - f_b) and the rays that meet the
//      other facet first (f_b); u3 chooses among them:
//        printed: with probabilities G = width / f_a (Sec. 6, "p(k) = G"); the share f_b / f_a and
//                 facets the light does not reach (f_a <= 0) produce no direction;
//        others:  s is taken as the facet met first, so with width / (f_a - f_b);
//   3. o from Eq. (5) in the cross-section, lifted back: o = c (-sin t_o a + cos t_o n) - (i.u) u.
// The density of o (per steradian) is what the routine produces: every path (s_m, k) that ends at
// o contributes its probability per d s times |ds/do| (Eq. 13),
//   pdf(o) = sum_k sum_m q(s_m) P(k | s_m) sin(theta_sm) / (k sin(theta_h)) / (4 cos(theta_d)),
// with the solutions s_m of kaleidoscope_solutions.h (the same as Eq. 16's). For the V-cavity's
// visible normals q P = D(s) <i.s> G / <i.n> (with |i.s| G the width of the k-outcome), so this pdf
// equals rho cos(theta_o) with F = 1 (Eq. 16): the routine samples the BRDF exactly, its weight
// is 1 up to rounding, and with Fresnel it is an average of the paths' Fresnel products. The
// printed p(o) = |s.n| D(s) G(i, o, s) lacks the sum over paths and the Jacobian |ds/do|: it is
// not a density (docs/ERRATA.md, E-IS1).
//
// Paths of more than max_k reflections are not returned (zero weight): pdf and BRDF both sum
// k <= max_k, and the light they carry (narrow grooves, theta_v < (pi - 2 |t_i|) / max_k) is the
// sampler's failure probability (sampler_failure_probability_3d); its part from paths beyond max_k
// alone is sampler_beyond_max_k_probability_3d, and a sample lost so says beyond_max_k. The default
// max_k, kSamplerMaxK = 16384, keeps that share below 1e-7 (fewer than one lost sample in 10^7)
// for GGX and Beckmann at every alpha in [0.01, 2] and Phong up to alpha 1 (GGX alpha 2, normal
// incidence: 3.7e-8; alpha 0.5, 30 deg: 1.4e-9; it falls as 1 / max_k^2). Phong above alpha 1 puts
// a share of its facets so close to vertical (D ~ cos^p, p < 0) that no max_k reaches it (alpha 2,
// 60 deg: 6.9e-3 at the default, 2.8e-3 at max_k 100000): the share is reported, not hidden. The
// pdf's cost near the retro direction grows with max_k where D does not vanish (`vgroove sample`,
// 10^5 samples, its cells' integrals: GGX alpha 0.5, 30 deg, 0.40 s at 256 and 2.4 s at 16384;
// Phong alpha 2, 60 deg, 1.1 s and 33 s), the draw's less (GGX: 0.95 against 1.2 us); Beckmann's
// sum stops where D underflows (ndf.h, D_vanishing_aperture; alpha 2, 60 deg: 0.38 s at 16384).
//
// Zero-weight returns (k = 0, pdf = 0, weight = 0, o = the mirror direction of i), all documented:
//   - the printed strategy's rays that meet the other facet first or a facet the light does not
//     reach (by design of the routine: 1 - the printed pdf's integral);
//   - a path with more than max_k reflections (above);
//   - i at or below the horizon; o at or below the horizon by rounding (grazing exits);
//   - o exactly at the mirror direction (h = n), where pdf and BRDF are both +inf (the k >= 2
//     terms diverge like 1 / sin(theta_h)): reached only by facets at exactly theta_s = 0 or
//     exactly 45 deg at normal incidence (measure zero; u0 = 0 gives theta_s = 0).
// Every returned o is finite and every returned pdf finite and > 0 or the zero-weight return
// (tests/analytic/sampling_3d_test.cpp, HardCases).
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
