// vgroove analytic: importance sampling of the nonsymmetric V-groove BRDF (Eq. 21-23,
// brdf_nonsymmetric.h, isotropic roughness, the independent partner law of Eq. 20) in 3D and
// flatland, the density of the directions it produces, and the weight rho cos / pdf.
//
// Lee, Jarabo, Jeon, Gutierrez, Kim. "Practical Multiple Scattering for Rough Surfaces".
// ACM TOG 37(6), 2018. Sec. 6 ("Nonsymmetric BRDF"), Eq. (7)-(9), (20)-(23).
//
// The routine (Sec. 6 with the first facet's law a choice, facet_strategy.h):
//   1. the facet hit first, s (u0, u1, u2), from the strategy's density q(s) (vndf.h): printed
//      |s.n| D(s), the V-cavity's visible normals (vndf), or the Smith-GGX ones (smith-vndf,
//      bounded-vndf); s leans towards a (its horizontal direction), tilt A: in the cross-section
//      (a, n) it is the left facet, theta_l = -A;
//   2. the partner's tilt B = theta_r (u3) from P(theta_r) (Eq. 20), by the tabulated inverse CDF
//      with binary search (partner_table.h). With isotropic D the partner law does not depend on s
//      (Sec. 5.2: P(theta_r | phi_v) is P(theta_r) when alpha does not depend on phi);
//   3. in the cross-section, light at t_i = atan2(-(i.a), i.n) (ERRATA E3D); Eq. (7) and (9) split
//      the rays aimed at s into zones of 1, k_b - 1, k_b, k_b + 1 reflections and the share f_b / f_a
//      that meets the partner first; u4 chooses a zone: printed with probabilities G (Eq. 9, the
//      Russian roulette of Sec. 6; the share f_b / f_a and unlit facets give no direction), the
//      others with G / (1 - f_b / f_a);
//   4. o from Eq. (8) in the cross-section, lifted back: o = c (-sin t_o a + cos t_o n) - (i.u) u.
// The density of o per steradian sums every path (first facet's orientation, family, B) that ends
// at o, with the Jacobian |ds/do| printed after Eq. (23) (brdf_nonsymmetric.h derives it):
//   pdf(o) = sum_k sum_first sum_families int dB q(s) P_tab(B) P(k | s, B) |ds/do|,
// over the same B-pieces as Eq. (23)'s integral (partner_pieces), by adaptive Gauss-Kronrod to the
// relative tolerance `tolerance` per piece. The pdf holds P itself (Eq. 20), as the BRDF does;
// the routine draws B from the table's P_tab, whose distance int |P_tab - P| dB < 1e-5
// (partner_table.h, tested) bounds the difference between pdf and the density of what is drawn
// (in any expectation of a function bounded by 1; the chi-square tests cannot resolve it). Holding
// P_tab in the pdf instead would make it exact but put 4096 kinks into every B-integral.
// The printed p(o) = |s_l.n| D(s_l) P(s_r | s_l) G is, as in the symmetric case, not a density
// (ERRATA E-IS1).
// Flatland: theta_s from the flatland strategy (theta_s < 0 the left facet, else the mirror
// image), P2 (Eq. 20's flatland analogue), the Jacobian |d theta_s / d theta_o| = 1 / (2 |d t_h / d
// theta_l|) = 1/k (k even), 1/(k+1) (k odd).
//
// Zero-weight returns (k = 0, pdf = 0, weight = 0, o = the mirror direction of i): the printed
// strategy's shadowed or unlit draws, fully shadowed draws of the others (f_b >= f_a: the partner
// takes every ray aimed at s), paths beyond max_k, i or o at or below the horizon (o by rounding),
// and o at h = n exactly (pdf +inf; measure zero). Their probability, integrated over the facets
// and the partner (not over o), is *_failure_probability: the pdf's normalization is checked
// against it (tests/analytic/sampling_nonsymmetric_test.cpp).
//
// Default max_k: kNonsymmetricSamplerMaxK = 256, because the pdf's cost grows as max_k (below): the
// share lost beyond it is ~1e-6 at GGX alpha 1 (2.4e-5 at 64), below one sample in the 10^4 to 10^5
// samples a run of this sampler affords.
//
// Cost: pdf and the weight integrate over B for each k <= max_k and both orientations (the BRDF's
// own evaluation, brdf_nonsymmetric.h, does the same): ~1 ms per pdf at tolerance 1e-9 and a few
// ms per sample (bench/sampling_bench.cpp), against ~1 us for the draw alone. A renderer would
// tabulate; here the pdf is the reference the tests hold the routine to.
#pragma once

#include "vgroove/analytic/brdf_3d.h"
#include "vgroove/analytic/facet_strategy.h"
#include "vgroove/analytic/partner_table.h"
#include "vgroove/analytic/sampling_3d.h"
#include "vgroove/analytic/sampling_flatland.h"

#include <array>

namespace vgroove::analytic {

inline constexpr int kNonsymmetricSamplerMaxK = 256;

// The sampler of one material: NDF, alpha, strategy and the partner table, built once.
struct NonsymmetricSampler {
  NdfKind ndf = NdfKind::ggx;
  double alpha = 0.5;
  SamplerOptions opt{FacetStrategy::vndf, kNonsymmetricSamplerMaxK};
  bool flatland = false;
  double tolerance = 1e-9;  // relative, per integrated B-piece of the pdf
  PartnerTable partner;     // P (3D) or P2 (flatland), tabulated
};

// Throws std::domain_error when the partner law does not exist (Phong, alpha >= sqrt(2)) or the
// strategy is not available (facet_strategy.h, strategy_supports).
NonsymmetricSampler make_nonsymmetric_sampler(NdfKind ndf, double alpha, const SamplerOptions& opt, bool flatland,
                                              int table_cells = kPartnerTableCells);

// ---- 3D -------------------------------------------------------------------------------------------

// u = (u0, u1, u2, u3, u4) in [0, 1)^5. F: the Fresnel plug-in of the weight's BRDF (Eq. 23).
// sample_nonsymmetric_3d = draw_nonsymmetric_3d (steps 1-4: o and k; k = 0 when no direction)
// followed by pdf(o) and the weight; the chi-square tests histogram the draws alone.
struct NonsymmetricDraw3d {
  Dir3 o;
  int k = 0;
  bool beyond_max_k = false;  // no direction because the drawn path has more than max_k reflections
};
NonsymmetricDraw3d draw_nonsymmetric_3d(const NonsymmetricSampler& s, const Dir3& i, const std::array<double, 5>& u);
VgrooveSample3d sample_nonsymmetric_3d(const NonsymmetricSampler& s, const Dir3& i, const std::array<double, 5>& u,
                                       const FresnelFn& F = {});
double nonsymmetric_pdf_3d(const NonsymmetricSampler& s, const Dir3& i, const Dir3& o);
double nonsymmetric_pdf_3d_k(const NonsymmetricSampler& s, const Dir3& i, const Dir3& o, int k_lo, int k_hi);
// The probability of no direction, over the facets and the partner (independent of pdf).
double nonsymmetric_failure_probability_3d(const NonsymmetricSampler& s, const Dir3& i, double tol = 1e-8);

// ---- Flatland (F = 1) -------------------------------------------------------------------------------

struct NonsymmetricDrawFlatland {
  double theta_o = 0.0;
  int k = 0;
  bool beyond_max_k = false;
};
NonsymmetricDrawFlatland draw_nonsymmetric_flatland(const NonsymmetricSampler& s, double theta_i,
                                                    const std::array<double, 5>& u);
VgrooveSampleFlatland sample_nonsymmetric_flatland(const NonsymmetricSampler& s, double theta_i,
                                                   const std::array<double, 5>& u);
double nonsymmetric_pdf_flatland(const NonsymmetricSampler& s, double theta_i, double theta_o);
double nonsymmetric_pdf_flatland_k(const NonsymmetricSampler& s, double theta_i, double theta_o, int k_lo, int k_hi);
double nonsymmetric_failure_probability_flatland(const NonsymmetricSampler& s, double theta_i, double tol = 1e-10);

}  // namespace vgroove::analytic
