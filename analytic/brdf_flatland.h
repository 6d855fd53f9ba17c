// vgroove analytic: the flatland (2D) multiple-scattering BRDF of a profile of symmetric V-grooves
// whose facet normals follow a flatland NDF, per bounce count k and summed, and its single-
// scattering (Cook-Torrance) analogue. Lee et al. 2018, Sec. 5.1 (Eq. 10-17) and 5.3 (Eq. 25),
// written for flatland: D2 (analytic/ndf.h) instead of D, theta instead of solid angle.
//
// Lee, Jarabo, Jeon, Gutierrez, Kim. "Practical Multiple Scattering for Rough Surfaces".
// ACM TOG 37(6), 2018.
//
// Conventions: those of analytic/kaleidoscope.h (angles from n, counter-clockwise positive,
// theta_i towards the light, a flat mirror gives theta_o = -theta_i). F = 1 throughout.
//
// The profile (sim/microsurface.h): symmetric V-grooves, peaks on one line; a groove of facet
// angle t has its left facet's normal at theta_s = -t, its right facet's at +t, aperture
// theta_v = pi - 2 t. D2(theta_s) d theta_s is the facet length with normals in d theta_s per
// unit macrosurface length (int D2 cos = 1).
//
// Derivation.
// (a) Flux on the facets, the flatland Eq. (10). A parallel beam carrying unit flux per unit
//     macrosurface length has width cos(theta_i) per unit length perpendicular to itself; the
//     facets with normals in d theta_s present the width D2(theta_s) cos(theta_i - theta_s)
//     d theta_s to it. Per unit incident flux they receive
//         d Phi_s = D2(theta_s) cos(theta_i - theta_s) d theta_s / cos(theta_i)      (facet lit).
//     For a unit facet, cos(theta_i - theta_s) is exactly f_a of Eq. (6) (the facet's projected
//     width), so d Phi_s = D2 f_a d theta_s / cos(theta_i).
// (b) Split by bounce count, Eq. (4)-(6) (corrected Eq. 6, ERRATA E1): the rays aimed at the facet
//     leave after n = k-1 reflections for the share (f_a - f_k)/f_a, after k for (f_k - f_b)/f_a,
//     and the share f_b/f_a hits the other facet first (it is counted there). Flux leaving
//     after n reflections from facets in d theta_s:
//         d Phi_n = D2(theta_s) w_n(theta_s) d theta_s / cos(theta_i),
//         w_{k-1} = f_a - f_k,  w_k = f_k - f_b.
//     F = 1 and peaks on a line: sum_facets int (f_a - f_b) D2 d theta_s / cos theta_i = 1 (each
//     groove passes its whole opening, 2 sin(theta_v/2) cos(theta_i) per unit facet): the
//     white furnace.
// (c) Exit angle, Eq. (5): theta_o = (-1)^n (theta_i + pi - n theta_v) for the left facet, with
//     theta_v = pi + 2 theta_s (theta_s = -t < 0); the right facet by the mirror theta -> -theta.
//     Hence the 2D Jacobian, the flatland Eq. (13):
//         |d theta_o / d theta_s| = |(-1)^n (-n) d theta_v/d theta_s| = 2 n,
//     the same on both facets and for every theta_s. (3D: sin theta_s / (k sin theta_h) /
//     (4 cos theta_d); the flatland factor 1/(2n) has neither the sin ratio nor the 1/cos theta_d,
//     which are solid-angle conversions.)
// (d) The BRDF, the flatland Eq. (12)/(14)/(16): rho2 cos(theta_o) d theta_o = d Phi_n, so
//         rho2(theta_i, theta_o; k) = sum_{solutions} D2(theta_s) w_k(theta_s)
//                                     / (2 k cos(theta_i) cos(theta_o)),
//     summed over every facet (left: theta_s < 0, right: theta_s > 0) whose Eq. (5) exit angle
//     after k reflections is theta_o. On the left facet, Eq. (5) inverted mod 2 pi gives
//         theta_v = (theta_i + pi - (-1)^k theta_o + 2 pi m) / k,   m integer, theta_v in (0, pi],
//     and w_k > 0 only for the theta_v whose Eq. (4) count is k or k + 1; the right facet is the
//     left one at (-theta_i, -theta_o). This is the analogue of m = 1, 2 in Eq. (16): in flatland
//     there are up to two solutions per facet side (the two adjacent k-pieces of Eq. 4), so up
//     to four in all. Normalized so that int rho2 cos(theta_o) d theta_o = albedo.
//     Eq. (17): flatland_brdf sums k = 1..max_k.
// (e) Single scattering, the flatland Eq. (1)-(3)/(25): with h = (theta_i + theta_o)/2,
//     theta_d = theta_o - h, d theta_h / d theta_o = 1/2 (not 1/(4 cos theta_d)):
//         rho_CT2 = D2(theta_h) cos(theta_d) G(i, o, h) / (2 cos theta_i cos theta_o),
//         G = min(G1(i, h), G1(o, h)) (V-cavity, Eq. 2-3).
//     The flatland Eq. (25) relation: rho_CT2 == rho2(.; k = 1) exactly. With k = 1 the only
//     solution is theta_s = h (Eq. 5, n = 1: theta_o = 2 theta_s - theta_i), cos(theta_i - h) =
//     cos(theta_d) = f_a, and in a 2D symmetric groove both shadowing and masking cut the lit
//     facet from its apex upwards (the opposite rim hides the bottom of the facet), so the
//     rays that are lit, reflect once and leave are exactly the fraction min(G1(i), G1(o)) of
//     f_a: w_1 = f_a G. The tests check it pointwise and per bin. In particular the V-cavity
//     at normal incidence has no shadowing, but still masking (G1(o) < 1 once theta_h > 30 deg,
//     theta_o = 2 theta_h), so the single albedo at theta_i = 0 is < 1: it is
//     int D2 cos(theta_h) min(1, 2 cos(2 theta_h))^+ d theta_h.
//
// Reciprocity. Per groove, the set of rays going from i to o after n reflections, reversed, is
// the set going from o to i after n reflections, and a beam's perpendicular width is kept by
// mirrors; the facet density per d theta_s does not depend on the direction and d theta_s/
// d theta_o = 1/(2n) both ways. So rho2(i, o; k) cos(theta_i) cos(theta_o) is symmetric per k
// (and summed over both facets: a single facet's term is not, since a path that starts on the
// left facet may end on the right one). The tests check it per k and summed.
//
// The binned lobe (flatland_lobe) integrates (b) over theta_v on each facet side, not over
// theta_o: on pieces between the breakpoints where Eq. (4)'s k changes (theta_v = (pi + 2
// theta_i)/m), where Eq. (6)'s clamps switch (f_b = 0, f_k = 0, f_k = f_b), where theta_o crosses
// a bin edge (Eq. 5 is linear in theta_v), and at points graded around the NDF's peak, the
// integrand is smooth; Gauss-Legendre on each.
// Limits.
// - Every n is resolved into bins up to n_resolved (>= max_k + 1, raised until the rest of the
//   flux is below 1e-13 or up to FlatlandLobeOptions::resolve_cap). The rest, grooves with theta_v
//   < (pi + 2|theta_i|)/(n_resolved + 1), is computed exactly in total (by_k, albedo) but binned by
//   its narrow-groove limit: Eq. (5) puts every ray of such a groove within theta_v of +-theta_i,
//   and the parity of n alternates from one k-piece to the next, so the flux goes half to the
//   bin of +theta_i and half to the bin of -theta_i (row max_k + 1). FlatlandLobe::tail reports
//   that flux; it matters for heavy-tailed NDFs (Phong with alpha > 1 has D2 ~ cos^p, p < 0,
//   and a tail ~ sqrt(theta_v)).
// - rho2 is defined on the open interval |theta_o| < pi/2; at |theta_o| = pi/2 (and beyond) the
//   functions return 0, the exit set there has measure zero.
#pragma once

#include "vgroove/analytic/ndf.h"

#include <atomic>
#include <vector>

namespace vgroove::analytic {

// Pointwise flatland BRDF rho2(theta_i, theta_o; k), F = 1, k >= 1, from the solutions Eq. (4)
// allows (kaleidoscope_solutions.h, in the frame where t_h <= 0, the profile being mirror
// symmetric) with Eq. (6)'s widths written as products, which keep their relative accuracy where
// the ends nearly meet and at the horizon.
double flatland_brdf_k(NdfKind ndf, double alpha, double theta_i, double theta_o, int k);
// Sum over k = 1..max_k in one pass over those solutions, whatever max_k is: the cost of a few k
// (at max_k 4096, ~2 us a pair where visiting every k and m took ~0.4 s).
double flatland_brdf(NdfKind ndf, double alpha, double theta_i, double theta_o, int max_k);
// The same as flatland_brdf (the name the furnace suite uses).
double flatland_brdf_fast(NdfKind ndf, double alpha, double theta_i, double theta_o, int max_k);
// The same sums evaluated straightforwardly, per k over every m of step (d) with Eq. (6) through
// G_kaleidoscopic (differences of sines): O(max_k^2), equal to the single pass to 1e-10 relative
// away from the horizon, and within ~1e-5 deg of it off by up to all of the value (the differences
// of offsets near 1 lose the widths there). The tests' independent route to the single pass.
double flatland_brdf_k_reference(NdfKind ndf, double alpha, double theta_i, double theta_o, int k);
double flatland_brdf_reference(NdfKind ndf, double alpha, double theta_i, double theta_o, int max_k);
// Single scattering (the Cook-Torrance analogue, V-cavity G).
double flatland_brdf_single(NdfKind ndf, double alpha, double theta_i, double theta_o);

// The fraction of the incident flux leaving into each theta_o bin, per k: the analytic
// counterpart of sim::MicrosurfaceTally, with the same layout (bins equal over (-pi/2, pi/2);
// rows k = 0..max_k, row max_k + 1 holds every k > max_k).
struct FlatlandLobe {
  int bins = 0;
  int max_k = 0;
  std::vector<double> by_k;          // [row]
  std::vector<double> theta_o;       // [bin], all k
  std::vector<double> theta_o_by_k;  // [row * bins + bin]
  double albedo = 0.0;               // sum of by_k
  int n_resolved = 0;                // bounce counts binned exactly: n <= n_resolved
  double tail = 0.0;                 // flux with n > n_resolved, binned by the narrow-groove limit
  double below = 0.0;                // flux the model sends below the horizon (expected 0)
};

struct FlatlandLobeOptions {
  int quadrature_order = 16;  // Gauss-Legendre points on the pieces with k <= 8 (fewer above)
  int resolve_cap = 4096;     // largest n_resolved
  // Read every 8 MB of the histogram's zeroing, before each bounce count's pieces and every 4096
  // bins a piece crosses (may be null): once set, the rest is skipped and the lobe is incomplete
  // (the caller, stopped by Ctrl-C, discards it). 10^5 bins at max_k 300 take ~3-5 s; set at any
  // moment, the lobe returns within 30 ms.
  const std::atomic<bool>* cancel = nullptr;
};

FlatlandLobe flatland_lobe(NdfKind ndf, double alpha, double theta_i, int bins, int max_k);
FlatlandLobe flatland_lobe(NdfKind ndf, double alpha, double theta_i, int bins, int max_k,
                           const FlatlandLobeOptions& opt);
// The single-scattering lobe (k = 1 only, V-cavity G): albedo < 1, the energy Cook-Torrance loses.
// Layout with max_k = 1 (everything in row 1). Integrated over theta_h from Eq. (1)-(3), not from
// the kaleidoscope, so that the tests compare two derivations.
FlatlandLobe flatland_single_lobe(NdfKind ndf, double alpha, double theta_i, int bins);

}  // namespace vgroove::analytic
