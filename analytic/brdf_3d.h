// vgroove analytic: the 3D multiple-scattering BRDF of symmetric V-grooves, Lee et al. 2018
// ("Practical Multiple Scattering for Rough Surfaces", ACM TOG 37(6)), Eq. (13)-(17), exact for
// the surface of grooves with coplanar ridges (sim/microsurface3d.h), and Cook-Torrance, Eq.
// (1)-(3) with the V-cavity G; Fresnel as a plug-in term per reflection (Eq. 11). Eq. (5) and (6)
// are taken at the projected angles t_i, t_o of the groove's cross-section (ERRATA E1, E3D).
// Accuracy: rho_k(i, o) = rho_k(o, i) bitwise, the sum over k within 7e-16 relative; against
// Eq. (16) in long double median 3e-16, worst 8e-12 relative; the batched pass (vgroove_brdf)
// within 1e-12 relative of vgroove_brdf_per_solution_reference; i or o at or below the horizon
// give 0, o at the mirror direction gives Cook-Torrance with G = 1 (k = 1) or +inf (k >= 2).
// Tests: tests/analytic/brdf_3d_test.cpp (Brdf3d.ReciprocityPerKAndForCookTorrance,
// Brdf3d.BatchedPassEqualsPerSolutionPass, Brdf3d.CookTorranceIsTheK1Term,
// Brdf3d.HardCasesAreFiniteOrTheDocumentedLimit, Brdf3d.Grazing*), against the tracer
// tests/validation/brdf_3d_sim_test.cpp. Timings: docs/performance.md.
// Derivation: docs/derivations/brdf_3d.md.
#pragma once

#include "vgroove/analytic/kaleidoscope.h"
#include "vgroove/analytic/kaleidoscope_solutions.h"
#include "vgroove/analytic/ndf.h"

#include <cmath>
#include <functional>
#include <vector>

namespace vgroove::analytic {

// Unit vectors in the frame of the macrosurface: n = (0, 0, 1). The direction at polar angle
// theta and azimuth phi is (sin theta cos phi, sin theta sin phi, cos theta).
struct Dir3 {
  double x = 0.0, y = 0.0, z = 1.0;
};
Dir3 dir3(double theta, double phi);

// The cross-section of the groove that holds h = (i + o)/|i + o| (the header's derivation): a is
// the horizontal direction of h, so that t_h = -theta_h <= 0 and the facet with normal h is the
// left one; x holds t_i = atan2(-(i.a), i.n) and t_o with their sines and cosines. Every field is
// computed symmetrically in (i, o) or swaps with them bitwise, which makes Eq. (16) reciprocal
// to the last bit.
struct GrooveFrame {
  CrossSection x;
  double c = 1.0;      // sqrt(1 - (i.u)^2) = sqrt(1 - (o.u)^2): the length of i's projection
  double sin_h = 0.0;  // sin(theta_h)
  double cos_d = 1.0;  // i.h = o.h
  double ax = 1.0, ay = 0.0;
};
// False when h = n exactly (the plane is undefined): then cos_d and sin_h = 0 hold, and the other
// fields are the section of the plane (x, z) (a = x). i and o above the horizon. The one frame of
// the symmetric and nonsymmetric BRDFs and samplers.
bool groove_frame(const Dir3& i, const Dir3& o, GrooveFrame& f);

// F(cos theta_incidence) -> reflectance in [0, 1]. An empty function means F = 1.
using FresnelFn = std::function<double(double)>;

// Eq. (16), F = 1: the k-resolved BRDF, k >= 1. i and o point away from the surface.
double vgroove_brdf_k(const Dir3& i, const Dir3& o, int k, NdfKind ndf, double alpha);
// Eq. (16) with the Fresnel plug-in.
double vgroove_brdf_k(const Dir3& i, const Dir3& o, int k, NdfKind ndf, double alpha, const FresnelFn& F);
// Eq. (17): the sum over k = 1..max_k.
double vgroove_brdf(const Dir3& i, const Dir3& o, NdfKind ndf, double alpha, int max_k);
double vgroove_brdf(const Dir3& i, const Dir3& o, NdfKind ndf, double alpha, int max_k, const FresnelFn& F);
// The same sums evaluated straightforwardly: per k, every j of Eq. (5) with theta_v in (0, pi]
// (O(max_k^2) candidates), where vgroove_brdf visits only the j that Eq. (4) allows (O(max_k)).
// The tests' reference for the single pass; F = 1.
double vgroove_brdf_k_reference(const Dir3& i, const Dir3& o, int k, NdfKind ndf, double alpha);
double vgroove_brdf_reference(const Dir3& i, const Dir3& o, NdfKind ndf, double alpha, int max_k);
// The same single pass as vgroove_brdf with each solution's term computed on its own (std::sin
// and std::cos per solution, the common factors per term): the plain form of the batched pass
// (brdf_3d_batch.cpp), for the tests and the benchmarks' side-by-side.
double vgroove_brdf_per_solution_reference(const Dir3& i, const Dir3& o, NdfKind ndf, double alpha, int max_k,
                                           const FresnelFn& F = {});
double vgroove_brdf_k_per_solution_reference(const Dir3& i, const Dir3& o, int k, NdfKind ndf, double alpha);
// The 2D width G f_a of Eq. (6) (corrected) of the outcome with exactly k reflections, for light
// at t_i aimed at `first` and leaving at t_o, where theta_v solves Eq. (5) for (t_i, t_o, k)
// (the form used by Eq. 16; derivation and numerics in kaleidoscope_solutions.h). Exposed for the tests.
double beam_width_k(double t_i, double t_o, double theta_v, int k, FacetSide first);
// Fresnel along a path of the cross-section: prod_j F(c |d_j . s_j|) over its k reflections, the
// first on `first` (Eq. 11 with the 3D cosines c times the 2D ones); 1 when F is empty.
double fresnel_along_path(const FresnelFn& F, double t_i, double theta_m, FacetSide first, int k, double c);
// Eq. (1)-(3): Cook-Torrance with the V-cavity G (Eq. 2), F = 1.
double cook_torrance(const Dir3& i, const Dir3& o, NdfKind ndf, double alpha);
double cook_torrance(const Dir3& i, const Dir3& o, NdfKind ndf, double alpha, const FresnelFn& F);

// The CDF of theta_m over the grooves' area, int_0^theta 2 pi D cos sin (closed forms), and its
// inverse. Exposed for the tests and the simulation's cross-checks.
double groove_cdf(NdfKind ndf, double alpha, double theta_m);
double groove_cdf_inverse(NdfKind ndf, double alpha, double u);
// The same theta_m with its cosine and sine, formed without trigonometry from the closed form
// (tan theta_m for GGX and Beckmann, 1 - cos theta_m for Phong): for the lobes' quadrature.
double groove_cdf_inverse(NdfKind ndf, double alpha, double u, double& cos_m, double& sin_m);
// The cosine and sine alone (no angle: no atan).
void groove_cdf_inverse_cos_sin(NdfKind ndf, double alpha, double u, double& cos_m, double& sin_m);

}  // namespace vgroove::analytic
