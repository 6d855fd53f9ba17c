// vgroove analytic: the multiple-scattering BRDF of nonsymmetric V-grooves, Lee et al. 2018
// ("Practical Multiple Scattering for Rough Surfaces", ACM TOG 37(6)), Eq. (21)-(25), in 3D
// (isotropic and anisotropic) and in flatland; point evaluation per bounce count k and summed.
// The partner's tilt B follows P(theta_r) (Eq. 20, analytic/partner_distribution.h) or B = A (the
// symmetric model); Eq. (23) is integrated over B by adaptive Gauss-Kronrod to the relative
// `tolerance` per piece, cut where Eq. (7)'s k_b changes. Readings: ERRATA E3D, E-NS2.
// Holds: the symmetric law reduces to Eq. (16) (1e-10), k = 1 is Cook-Torrance with the partner-
// averaged G, per-k reciprocity, never NaN (0 at or below the horizon; at the mirror direction
// k = 1 is Cook-Torrance with G = 1 and k >= 2 is +inf or 0). Phong needs alpha < sqrt(2).
// Tests: tests/analytic/brdf_nonsymmetric_test.cpp (NonsymmetricBrdf.SymmetricLimitIsEq16,
// NonsymmetricBrdf.Eq23JacobianMatchesTheExactGrooveMap, NonsymmetricBrdf.ReciprocalPerK,
// NonsymmetricBrdf.SingleReflectionIsCookTorrance, NonsymmetricBrdf.HardCasesAreFiniteOrTheDocumentedLimit).
// Derivation: docs/derivations/nonsymmetric.md.
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
