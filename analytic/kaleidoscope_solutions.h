// vgroove analytic: the inverse of the symmetric kaleidoscope. For the light at t_i and an exit at
// t_o in a groove's cross-section, every (facet hit first, bounce count k, aperture theta_v) of
// Eq. (5) whose outcome of exactly k reflections has a non-empty beam in Eq. (6), with the beam's
// width. The 3D BRDF (brdf_3d.h, Eq. 16), the flatland BRDF and the samplers' pdfs sum over these.
// Lee et al. 2018 ("Practical Multiple Scattering for Rough Surfaces", ACM TOG 37(6)), Sec. 4.1,
// Eq. (4)-(6); Sec. 5.1, Eq. (15)-(16). Conventions of kaleidoscope.h; the frame has t_h <= 0.
// beam_width is one intersection of four offsets that the reversed path permutes (reciprocal term
// by term), differences of sines written as products (relative accuracy where the ends meet);
// for_each_solution visits j = 0 and k in [X / pi, X / |a + b|] (plus neighbours against rounding).
// Tests: tests/analytic/brdf_3d_test.cpp (Brdf3d.BeamWidthIsEq6, Brdf3d.BeamWidthIsEq6AtTheHorizon,
// Brdf3d.SinglePassEqualsPerKEvaluation), tests/analytic/brdf_flatland_test.cpp
// (FlatlandBrdf.SinglePassEqualsEveryMReference).
// Derivation: docs/derivations/brdf_3d.md.
#pragma once

#include "vgroove/analytic/kaleidoscope.h"

#include <algorithm>
#include <cmath>
#include <numbers>

namespace vgroove::analytic {

// The incident and exit angles in a cross-section, with their sines and cosines (given, so that a
// 3D caller can pass values computed from the vectors) and the cosines of the half sum and
// difference: cos((t_i + t_o)/2) = cos(t_h), cos((t_i - t_o)/2), and |sin((t_i + t_o)/2)| =
// sin(theta_h).
struct CrossSection {
  double t_i = 0.0, t_o = 0.0;
  double sin_ti = 0.0, cos_ti = 1.0, sin_to = 0.0, cos_to = 1.0;
  double cos_half_sum = 1.0, cos_half_diff = 1.0;
  double sin_half_sum = 0.0;
  // The k = 1 solution takes S and C from cos_half_sum and sin_half_sum (half_aperture_cos_sin):
  // where h grazes the cross-section's horizon, and in 3D where i is nearly opposite to o (the
  // groove's azimuth, hence t_i and t_o, then rests on the inputs' last bits; h does not).
  bool single_from_h = false;
};
// From the two angles alone.
CrossSection cross_section(double t_i, double t_o);

// One facet-first path family of Eq. (5) in the frame of the facet hit first (the right facet
// mirrored: t -> -t): a = the incident angle, b = (-1)^k times the exit angle. Only the parity of
// k matters.
struct Ends {
  double a, b, sin_a, cos_a, sin_b, cos_b;
  double cos_half_diff, cos_half_sum;  // cos((a - b)/2), cos((a + b)/2)
};
Ends ends_of(const CrossSection& p, FacetSide side, int k);

// Whether the k-outcome can be non-empty at theta_v (the test of Eq. 4, written with products; see
// brdf_3d.cpp): both rims lit and K in {k, k + 1} for the path and for its reverse.
bool outcome_possible(const Ends& e, double theta_v, int k);

// The width G f_a of Eq. (6) (corrected, ERRATA E1) of the k-reflection outcome, in the units of
// Eq. (6) (unit facets), for theta_v solving Eq. (5) for the ends e; S = sin(theta_v/2) =
// cos(theta_m), C = cos(theta_v/2) = sin(theta_m). Called only where outcome_possible holds.
double beam_width(const Ends& e, double theta_v, double S, double C, int k);

// The solutions of Eq. (5): theta_v = (a - b + (2 j + 1) pi) / k.
inline double solution_theta_v(double a_minus_b, int j, int k) {
  return (a_minus_b + (2.0 * j + 1.0) * std::numbers::pi) / k;
}

// cos(t_h) (h.z in 3D) below which the k = 1 solution takes its S and C from the cross-section
// (CrossSection::single_from_h), and vgroove_brdf the per-solution pass (brdf_3d.cpp): h within
// 0.29 deg of the cross-section's horizon, theta_v = pi - 2 |t_h| < 0.01.
inline constexpr double kGrazingHalfVector = 5e-3;

// S = sin(theta_v/2) = cos(theta_m) and C = cos(theta_v/2) = sin(theta_m) of a solution. For k = 1
// (s = h: theta_v/2 = t_h + pi/2) they are the cross-section's cos(t_h) and sin(theta_h), which a
// 3D caller forms from h itself, where p.single_from_h: sin(theta_v/2) of the rounded theta_v =
// pi + t_i + t_o carries ulp(pi) / theta_v relative (up to all of S at the horizon, theta_v -> 0;
// below 4.4e-14 above kGrazingHalfVector, where the same bits as before are kept), and in 3D the
// angles' own error where i is nearly opposite to o.
inline void half_aperture_cos_sin(const CrossSection& p, int k, double theta_v, double& S, double& C) {
  if (k == 1 && p.single_from_h) {
    S = p.cos_half_sum;
    C = p.sin_half_sum;
    return;
  }
  const double half = 0.5 * theta_v;
  S = std::sin(half);
  C = std::cos(half);
}

// One solution with a non-empty beam.
struct Solution {
  FacetSide first;  // the facet hit first
  int k;            // reflections
  double theta_v;   // aperture
  double S, C;      // sin(theta_v/2) = cos(theta_m), cos(theta_v/2) = sin(theta_m)
  double W;         // G f_a of Eq. (6): the k-outcome's width, > 0
  const Ends* e;
  // f_a = sin(theta_v/2 - a): the facet's projected width (its 2D cosine of incidence), and the
  // lit width f_a - max(0, f_b): the part of the beam that meets this facet first.
  double f_a() const { return S * e->cos_a - C * e->sin_a; }
  double lit() const {
    const double f_b = -(S * e->cos_a + C * e->sin_a);
    return f_b > 0.0 ? 2.0 * S * e->cos_a : f_a();  // f_a - f_b = 2 sin(theta_v/2) cos(a)
  }
};

// The k = 1 solution (s = h), the left facet's j = 0 in the frame t_h <= 0: theta_v = pi + t_i + t_o.
// It exists wherever theta_v <= pi: both rims are lit and Eq. (4) gives K in {1, 2} for the path
// and its reverse for any a, b in (-pi/2, pi/2) (outcome_possible's tests reduce to that for
// k = 1), so only its width can vanish. It is not put to those tests, nor to theta_v > 0: where
// both directions graze the horizon their operands (pi + 2a, theta_v itself) are of the order of
// the angles' rounding and said no to a width of 2 cos(t_h) cos(t), S and C being the frame's.
template <class Fn>
void visit_single_reflection(const CrossSection& p, Fn&& fn, double theta_v_min) {
  const Ends e = ends_of(p, FacetSide::left, 1);
  const double theta_v = std::max(0.0, solution_theta_v(e.a - e.b, 0, 1));
  if (theta_v < theta_v_min || !(theta_v <= std::numbers::pi)) return;
  double S, C;
  half_aperture_cos_sin(p, 1, theta_v, S, C);
  const double W = beam_width(e, theta_v, S, C, 1);
  if (W > 0.0) fn(Solution{FacetSide::left, 1, theta_v, S, C, W, &e});
}

// Calls fn(const Solution&) for every solution with k in [k_lo, k_hi] and W > 0, in a fixed order
// (facet, parity, j, k). k = 1: s = h is the left facet (the frame's choice t_h <= 0; visited
// first, visit_single_reflection); the right facet's k = 1 solution exists only as the rounding
// image of t_h = 0 and is skipped. Apertures below theta_v_min are not visited (a caller's D is 0
// there: ndf.h, D_vanishing_aperture).
template <class Fn>
void for_each_solution(const CrossSection& p, int k_lo, int k_hi, Fn&& fn, double theta_v_min = 0.0) {
  if (k_lo <= 1 && k_hi >= 1) visit_single_reflection(p, fn, theta_v_min);
  for (FacetSide side : {FacetSide::left, FacetSide::right}) {
    for (int k_first : {1, 2}) {
      const Ends e = ends_of(p, side, k_first);  // depends on the parity of k only
      const double d = e.a - e.b;
      const double span = std::numbers::pi + 2.0 * e.a;
      for (int j = -1; j <= 1; ++j) {
        const double X = d + (2.0 * j + 1.0) * std::numbers::pi;
        if (!(X > 0.0)) continue;
        // outcome_possible holds only while k m <= X, m = max(|X - span|, 2a, -2b): Eq. (4)'s
        // k |X - span| <= X and both rims lit, theta_v = X / k > 2a and > -2b (the batched pass's
        // bound, brdf_3d_batch.cpp). Near the horizon |X - span| alone allowed up to max_k
        // candidates that the rims all refused (10 ms a pair at max_k 10^6). One k more against
        // rounding; outcome_possible decides.
        const double dev = std::max({std::abs(X - span), 2.0 * e.a, -2.0 * e.b});
        // In double until clamped: X / dev may exceed any int.
        const double k_top = dev > 0.0 ? std::floor(X / dev) + 1.0 : static_cast<double>(k_hi);
        const int k_end = static_cast<int>(std::min(static_cast<double>(k_hi), k_top));
        int k = std::max(k_lo, static_cast<int>(std::ceil(X / std::numbers::pi)) - 1);
        if (k < 1) k = 1;
        if ((k - k_first) % 2 != 0) ++k;  // the parity of this pass
        for (; k <= k_end; k += 2) {
          if (k == 1) continue;  // visit_single_reflection
          const double theta_v = solution_theta_v(d, j, k);
          if (theta_v < theta_v_min) break;  // theta_v falls as k grows
          if (!(theta_v > 0.0 && theta_v <= std::numbers::pi)) continue;
          if (!outcome_possible(e, theta_v, k)) continue;
          double S, C;
          half_aperture_cos_sin(p, k, theta_v, S, C);
          const double W = beam_width(e, theta_v, S, C, k);
          if (!(W > 0.0)) continue;
          fn(Solution{side, k, theta_v, S, C, W, &e});
        }
      }
    }
  }
}

// The same solutions visited straightforwardly, one k at a time and every j with theta_v in
// (0, pi] (O(k) candidates per k): the reference the tests hold the single pass to.
template <class Fn>
void for_each_solution_every_j(const CrossSection& p, int k, Fn&& fn) {
  if (k == 1) {
    visit_single_reflection(p, fn, 0.0);
    return;
  }
  for (FacetSide side : {FacetSide::left, FacetSide::right}) {
    const Ends e = ends_of(p, side, k);
    const double d = e.a - e.b;
    const int j_lo = static_cast<int>(std::ceil((-d - std::numbers::pi) / (2.0 * std::numbers::pi)));
    const int j_hi =
        static_cast<int>(std::floor((k * std::numbers::pi - d - std::numbers::pi) / (2.0 * std::numbers::pi)));
    for (int j = j_lo; j <= j_hi; ++j) {
      const double theta_v = solution_theta_v(d, j, k);
      if (!(theta_v > 0.0 && theta_v <= std::numbers::pi)) continue;
      if (!outcome_possible(e, theta_v, k)) continue;
      double S, C;
      half_aperture_cos_sin(p, k, theta_v, S, C);
      const double W = beam_width(e, theta_v, S, C, k);
      if (!(W > 0.0)) continue;
      fn(Solution{side, k, theta_v, S, C, W, &e});
    }
  }
}

}  // namespace vgroove::analytic
