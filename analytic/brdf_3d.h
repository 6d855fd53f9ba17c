// vgroove analytic: the 3D multiple-scattering BRDF of symmetric V-grooves, Lee et al. 2018,
// Eq. (13)-(17), and Cook-Torrance, Eq. (1)-(3) with the V-cavity G; Fresnel as a plug-in term.
//
// Lee, Jarabo, Jeon, Gutierrez, Kim. "Practical Multiple Scattering for Rough Surfaces".
// ACM TOG 37(6), 2018. Sec. 3 (Eq. 1-3), Sec. 5.1 (Eq. 10-17), Sec. 5.3 (Eq. 24-25), App. A.
//
// The microsurface (shared with sim/microsurface3d.h). n = (0,0,1); infinitely long symmetric
// grooves with coplanar ridges; a groove of azimuth phi_a in [0, pi) has the horizontal axis
// a = (cos phi_a, sin phi_a, 0), u = n x a, facet normals s = dir(theta_m, phi_a) (the "left"
// facet of the 2D model in the cross-section (a, n)) and s' = dir(theta_m, phi_a + pi) (the
// "right" one), aperture theta_v = pi - 2 theta_m. Grooves cover the macrosurface with the area
// fraction 2 D(theta_m) cos(theta_m) sin(theta_m) d theta_m d phi_a.
//
// Derivation (exact for this microsurface). Inside a groove the component of the travel
// direction along u is kept and the cross-section sees the 2D kaleidoscope (analytic/
// kaleidoscope.h) at the PROJECTED incident angle t_i = atan2(-(i.a), i.n). The exit o =
// c (e_x a + e_y n) - (i.u) u, c = sqrt(1 - (i.u)^2), so i + o = c (p + e) lies in the
// cross-section: the half vector h is in the plane (a, n), its 2D angle is t_h = (t_i + t_o)/2,
// theta_h = |t_h|, and o is the mirror image of i about h. Therefore, at fixed i:
//   d omega_o = 4 (i.h) d omega_h                           (reflection about h),
//   d omega_h = sin(theta_h) |d t_h / d theta_m| d theta_m d phi_a = k sin(theta_h) d theta_m d phi_a
// (the map (theta_m, phi_a) -> (t_h, phi_a) is triangular and Eq. (5) gives d t_o / d theta_v = -+k,
// d theta_v = -2 d theta_m, so d t_h / d theta_m = +-k), and with d s = sin(theta_m) d theta_m d phi_a,
//   |ds/do| = sin(theta_s) / (k sin(theta_h)) / (4 cos(theta_d)),          cos(theta_d) = i.h,
// which is Eq. (13) as printed. The flux: a groove receives the fraction 2 D cos sin d theta_m
// d phi_a of the incident flux and sends the fraction P = G f_a / w of it into k bounces via the
// facet hit first (G and f_a from Eq. (6) at t_i, w = 2 cos(theta_m) cos(t_i) the opening width).
// Since |i.s| = c f_a and cos(theta_i) = c cos(t_i), 2 cos(theta_m) P = G |i.s| / cos(theta_i),
// and dividing by d omega_o and cos(theta_o) gives Eq. (16) exactly, with
//   - G(i, o, s) = the 2D Eq. (6) fraction (corrected form, ERRATA E1) of the facet hit first,
//     evaluated at the projected angle t_i, and
//   - s_m the solutions of Eq. (5) written with the projected angles t_i, t_o (not the 3D
//     theta_i, theta_o: App. A Eq. (27) holds in the plane of incidence only; see ERRATA E3D).
// The solutions: for the facet hit first (left or right) and k, theta_v = (+-t_i + pi -+ (-1)^k
// t_o + 2 pi j) / k; every j with theta_v in (0, pi] and an Eq. (6) outcome of exactly k
// reflections counts. "m = 1, 2" of Eq. (16) is generically one solution per facet, but the
// code sums whatever exists.
//
// Limits (documented, never NaN):
//   - o at the mirror direction exactly (h = n, the plane (a, n) undefined): k = 1 returns the
//     limit sin(theta_s)/sin(theta_h) -> 1, i.e. Cook-Torrance with G = 1; k >= 2 returns +inf
//     (the 1/sin(theta_h) of Eq. (14) diverges there; its integral over any bin is finite).
//   - i or o at or below the horizon (cos <= 0): 0 (no flux arrives or leaves there; the set is
//     of measure zero, and rho cos(theta_o) -> 0 there because the rims mask grazing exits).
//     Above it, down to cos = 2.8e-16 (89.99999999999999 deg, the edge of the range the command
//     line and Python accept; dir3 of 90 deg itself has cos 6.1e-17), rho keeps its finite limit:
//     per k reciprocal bitwise and k = 1 Cook-Torrance to 1e-10 (Brdf3d.Grazing*: the widths'
//     ends chosen from their products where the offsets tie, k = 1's S and C from h where h
//     grazes, the projections of light running along the groove formed as unit vectors have
//     them; brdf_3d.cpp, kaleidoscope_solutions.h).
//
// Fresnel: the plug-in F(cos) -> reflectance is applied per reflection, prod_j F(|d_j . s_j|),
// with the 3D cosines |d_j . s_j| = c |d_j' . s_j'| from the 2D path in the cross-section.
//
// Evaluation (brdf_3d.cpp). The width G f_a of Eq. (6) is written with the exit angle (Eq. 5
// turns Eq. 6's transition point into a function of t_o), as one intersection of offsets that
// the reversed path permutes, each difference of sines as a product (beam_width):
//   - reciprocity: rho_k(i, o) = rho_k(o, i) bitwise (20 000 random pairs, k = 1..6), the sum
//     over k = 1..16 within 7e-16 relative (the order of the terms); a difference of sines
//     would be off by up to 3e-11;
//   - accuracy against Eq. (16) in long double from the same (i, o) (GGX, 20 000 pairs x k 1..6):
//     median 3e-16, 99.9 % below 1.1e-13, worst 8e-12 relative. The
//     worst cases sit within ~1e-5 of the edge of a k's support, where rho_k vanishes linearly:
//     there the rounding of t_i, t_o themselves (atan2) sets a relative error ~1e-16 / width;
//   - cost: the solutions of Eq. (5) that Eq. (4) allows have j = 0 and k in [X / pi, X / |a + b|]
//     (for_each_solution, kaleidoscope_solutions.h), so one pass visits them all, ~3-4.5 solutions per (i, o), for any
//     max_k. vgroove_brdf takes them four at a time without branches (brdf_3d_batch.cpp: vector
//     lanes, polynomial sines, the common factors once); the plain evaluation, each solution's
//     term on its own, is vgroove_brdf_per_solution_reference (values within 1e-12 relative,
//     measured 2.5e-14 worst in groove_frame). For GGX and Beckmann the batched pass also takes the
//     plane from groove_frame_fast (brdf_3d.cpp: both angles at once by atan2_pair, no normalized
//     h; values within 6.7e-15 (GGX) and 4.6e-14 (Beckmann) relative of the per-solution pass in
//     groove_frame). Beckmann's tails multiply an ulp of t_i by up to ~10^5: its pass in that frame
//     bounds the amplification pair by pair and declines the far tail, which it evaluates again
//     in groove_frame (brdf_3d_batch.cpp); Phong keeps groove_frame.
//     Measured (bench/brdf_bench.cpp, 1024 cosine-weighted pairs, alpha 0.3 and 1.0, medians
//     of 5 interleaved repetitions): GGX ~130 ns at max_k 4 and ~160 ns at max_k 16 against ~72 ns
//     for cook_torrance (1.8-1.9x and 2.2x), Beckmann 150-160 and ~194 against ~83 (1.8-1.9x and
//     2.3-2.4x); the library's frame alone (two atan2, a hypot, ten divisions)
//     had cost about one Cook-Torrance. The straightforward per-k evaluation (every j)
//     stays as vgroove_brdf_k_reference for the tests.
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
