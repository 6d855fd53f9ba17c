// vgroove analytic: the multiple-scattering BRDF of nonsymmetric V-grooves, Lee et al. 2018,
// Eq. (21)-(25), in 3D (isotropic and anisotropic) and in flatland; point evaluation per bounce
// count k and summed.
//
// Lee, Jarabo, Jeon, Gutierrez, Kim. "Practical Multiple Scattering for Rough Surfaces".
// ACM TOG 37(6), 2018. Sec. 4.2 (Eq. 7-9), Sec. 5.2 (Eq. 18-23), Sec. 5.3 (Eq. 24-25), App. C.
//
// The microsurface (sim/microsurface_nonsymmetric.h). Grooves with coplanar ridges whose facets lie
// in the cross-section (a, n), a = (cos phi_a, sin phi_a, 0): the facet hit first has its normal
// s = dir(A, phi_s), tilt A, distributed by D in projected area; its partner has the tilt B,
// distributed by P(B | phi_s) (analytic/partner_distribution.h, Eq. 20) independently (or B = A:
// the symmetric model). In the cross-section oriented so that the first facet leans towards +a it
// is the left facet of Eq. (7)-(9): theta_l = -A, theta_r = B.
//
// Derivation (3D; the same steps as Eq. 16, analytic/brdf_3d.h). Light from i, per unit incident
// flux, reaches the first facets with normals in ds and partners in dB with the fraction
//   |i.s| D(s) ds P(B) dB / cos(theta_i)                                           (Eq. 21)
// (D in projected area per macro area: |i.s| D ds is their area seen from i). Inside a groove the
// component of the travel direction along the axis u = n x a is kept and the cross-section sees
// the 2D kaleidoscope at the projected angle t_i = atan2(-(i.a), i.n) (ERRATA E3D); o is the
// mirror image of i about h, which lies in the cross-section, and t_h = (t_i + t_o)/2. Of the rays
// aimed at the first facet, the fraction G (Eq. 9, for the facet hit first, at t_i) leaves after k
// reflections along Eq. (8)'s t_o. At fixed B the map (A, phi_a) -> o is triangular:
//   d omega_o = 4 (i.h) d omega_h,  d omega_h = sin(theta_h) |d t_h / d theta_l| dA d phi_a,
//   |d t_h / d theta_l| = 0.5 |0.5 - (-1)^k (k + 0.5)| = k/2 (k even), (k+1)/2 (k odd)   (Eq. 8),
// and ds = sin(A) dA d phi_a, so
//   |ds/do| = sin(A) / (0.5 |0.5 - (-1)^k (k + 0.5)| sin(theta_h)) / (4 cos(theta_d)),
// the Jacobian printed after Eq. (23). Dividing the flux by cos(theta_o) d omega_o:
//   rho(i, o; k) = sum_{first} int dB [ |i.s| G D(s) P(B | phi_s) |ds/do| ] / (cos theta_i cos theta_o),
// Eq. (23), with these readings:
//   - "first" runs over the two orientations of the cross-section through h: the first facet
//     leaning towards h's horizontal direction (left in the frame of brdf_3d.h, t_h <= 0) or away
//     from it (right; mirrored: t -> -t). This is the paper's "invert the parameters" for the facet
//     hit first; its "theta_r in [-pi/2, pi/2]" spans the same two cases with B = |theta_r| when P
//     is normalized on [0, pi/2) (ERRATA E-NS2);
//   - theta_l(B) solves Eq. (8) for (t_i, t_o, k) at fixed theta_r = B, modulo 2 pi:
//       k even: theta_l = B + (t_i - t_o + (1 - k) pi + 2 pi j) / k,
//       k odd:  theta_l = ((k - 1) B + t_i + t_o + (1 - k) pi + 2 pi j) / (k + 1),
//     each j with theta_l in (-pi/2, 0], B in [0, pi/2) and an aperture pi + theta_l - B > 0 is
//     one family of grooves; G > 0 only where Eq. (7)'s k_b is within one of k (or k = 1);
//   - |i.s| G = c f_k / l_L: c = |i_perp| = sqrt(1 - (i.u)^2), f_k the width of Eq. (9)'s zones
//     of exactly k reflections and l_L the first facet's length (both with the longer facet of
//     unit length; f_a / l_L = cos(t_i - theta_l) is the 2D cosine of incidence).
// k = 1 (Eq. 25): theta_l = t_h does not depend on B, s = h, and |ds/do| = 1 / (4 cos theta_d) times
// sin(A) / sin(theta_h) = 1: rho_1 = D(h) G_1 / (4 cos theta_i cos theta_o), Cook-Torrance with the
// single-reflection share of Eq. (9) averaged over the partner, G_1 = int P(B) f_1 / f_a dB. With
// B = A (the symmetric model) it is Cook-Torrance with the V-cavity G.
// The symmetric model (P = delta(B - A), Eq. 24): along a family A(B) = -theta_l(B), so the delta
// integrates to 1 / |1 + d theta_l / dB| = 1/2 (k even), (k+1)/(2k) (k odd); times 1 / |d t_h /
// d theta_l| this is 1/k, Eq. (13)'s factor: Eq. (23) reduces to Eq. (16) (tested to 1e-10).
// Flatland (analytic/brdf_flatland.h's steps): rho2(theta_i, theta_o; k) = sum_first int dB D2(A)
// P2(B) f_k / l_L / (|d theta_o / d theta_l| cos theta_i cos theta_o), |d theta_o / d theta_l| =
// k (k even), k + 1 (k odd); the first facet on the left (theta_s = -A) or right (mirrored).
//
// Evaluation. Per family, the B range is cut where Eq. (7)'s k_b changes (theta_l is linear in B,
// so k_b's argument is a ratio of linear functions: closed-form cuts); on each piece the widths of
// Eq. (9) are maxima and minima of smooth functions (kinks where two of them cross), integrated by
// adaptive Gauss-Kronrod (7-15 points) to the relative tolerance `tolerance` of the piece.
//
// Limits (never NaN): i or o at or below the horizon: 0. o at the mirror direction exactly (h = n,
// no cross-section): k = 1 returns Cook-Torrance with G = 1 (the flat facet reflects everything
// once: the limit); k >= 2 returns +inf when grooves send light there (the 1/sin(theta_h) of the
// Jacobian, integrable), else 0. Phong needs alpha < sqrt(2) for the independent partner law
// (std::domain_error otherwise, analytic/partner_distribution.h).
#pragma once

#include "vgroove/analytic/brdf_3d.h"
#include "vgroove/analytic/ndf_anisotropic.h"

#include <vector>

namespace vgroove::analytic {

enum class PartnerLaw : unsigned char {
  independent,  // Eq. (20): the partner's tilt drawn independently of the first facet's
  symmetric,    // B = A: the symmetric model (Eq. 24 reduces Eq. 23 to Eq. 16)
};

struct NonsymmetricModel {
  Roughness roughness;  // anisotropic in 3D only; directions in the frame of the alpha_x axis
  PartnerLaw partner = PartnerLaw::independent;
  // > 0: instead of `partner`, B uniform on [A - w, A + w] (a narrow conditional law for the
  // symmetric limit's tests).
  double near_symmetric_halfwidth = 0.0;
  double tolerance = 1e-9;  // relative, per integrated piece
};

// Eq. (23), F = 1 or with the Fresnel plug-in: k >= 1; i and o point away from the surface.
double vgroove_nonsymmetric_brdf_k(const Dir3& i, const Dir3& o, int k, NdfKind ndf, double alpha);
double vgroove_nonsymmetric_brdf_k(const Dir3& i, const Dir3& o, int k, NdfKind ndf, double alpha, const FresnelFn& F);
// Eq. (17) with Eq. (23): the sum over k = 1..max_k.
double vgroove_nonsymmetric_brdf(const Dir3& i, const Dir3& o, NdfKind ndf, double alpha, int max_k);
double vgroove_nonsymmetric_brdf(const Dir3& i, const Dir3& o, NdfKind ndf, double alpha, int max_k,
                                 const FresnelFn& F);
// The general forms: anisotropic roughness, the partner law.
double nonsymmetric_brdf_k(const Dir3& i, const Dir3& o, int k, const NonsymmetricModel& m, const FresnelFn& F = {});
double nonsymmetric_brdf(const Dir3& i, const Dir3& o, int max_k, const NonsymmetricModel& m, const FresnelFn& F = {});

// Flatland, F = 1: rho2(theta_i, theta_o; k) and the sum over k (roughness.alpha_x; isotropic).
double flatland_nonsymmetric_brdf_k(double theta_i, double theta_o, int k, const NonsymmetricModel& m);
double flatland_nonsymmetric_brdf(double theta_i, double theta_o, int max_k, const NonsymmetricModel& m);

// The width of Eq. (9)'s zones with exactly k reflections (summed), for light at t_i aimed at the
// left facet of the groove (theta_l, theta_r), and the left facet's length, both with the longer
// facet of unit length; with f_a (the lit width, 0 when unlit) and f_b (the part that meets the
// partner first), so that width / f_a is Eq. (9)'s G of count k. Exposed for the tests (checked
// against G_nonsymmetric) and for the sampler's pdf (sampling_nonsymmetric.cpp).
struct CountWidth {
  double width = 0.0;
  double len_left = 0.0;
  double f_a = 0.0, f_b = 0.0;
};
CountWidth count_width(double t_i, double theta_l, double theta_r, int k);

// The grooves that send t_i to t_o after k reflections with the left facet hit first, as Eq. (23)'s
// integral visits them: along a family theta_l = C + beta B (the inversions of Eq. 8 above) the
// B-intervals [lo, hi] with constant k_b that can hold a k-reflection outcome. Exposed for the
// nonsymmetric sampler's pdf (analytic/sampling_nonsymmetric.h), which integrates its own density
// over the same pieces.
struct PartnerPiece {
  double C = 0.0, beta = 0.0, lo = 0.0, hi = 0.0;
};
std::vector<PartnerPiece> partner_pieces(double t_i, double t_o, int k);

}  // namespace vgroove::analytic
