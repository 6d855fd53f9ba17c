// vgroove analytic (internal to brdf_3d*.cpp): the terms of Eq. (16), one facet solution of
// Eq. (5) at a time, shared by the evaluation passes of brdf_3d.cpp (per solution, the previous
// path, kept as vgroove_brdf_per_solution_reference) and brdf_3d_batch.cpp (batched). Not part of
// the API: names live in vgroove::analytic::brdf_terms and may change.
//
// Lee, Jarabo, Jeon, Gutierrez, Kim. "Practical Multiple Scattering for Rough Surfaces".
// ACM TOG 37(6), 2018. Sec. 5.1 (Eq. 13-17). The derivation is in brdf_3d.h.
#pragma once

#include "vgroove/analytic/brdf_3d.h"
#include "vgroove/analytic/kaleidoscope.h"

#include <algorithm>
#include <cmath>
#include <numbers>

namespace vgroove::analytic::brdf_terms {

inline double dot(const Dir3& a, const Dir3& b) { return a.x * b.x + a.y * b.y + a.z * b.z; }

// The cross-section of the groove that holds h: the 2D angles of i, o and h, and c = |i_perp|.
// Every field is computed symmetrically in (i, o) or swaps with them bitwise (t_i <-> t_o, ...),
// so that the evaluation below is reciprocal to the last bit (see beam_width).
struct Plane {
  double t_i = 0.0, t_o = 0.0;
  double c = 1.0;      // sqrt(1 - (i.u)^2) = sqrt(1 - (o.u)^2): the length of i's projection
  double sin_h = 0.0;  // sin(theta_h)
  double cos_d = 1.0;  // i.h = o.h
  double sin_ti = 0.0, cos_ti = 1.0, sin_to = 0.0, cos_to = 1.0;
  double cos_half_sum = 1.0;   // cos((t_i + t_o)/2)
  double cos_half_diff = 1.0;  // cos((t_i - t_o)/2)
};

// h = (i + o)/|i + o|, a = the horizontal direction of h, so that the 2D angle of h is -theta_h <= 0
// and the facet with normal h is the "left" one (2D angle -theta_m). Returns false when h = n exactly.
inline bool make_plane(const Dir3& i, const Dir3& o, Plane& p) {
  Dir3 h{i.x + o.x, i.y + o.y, i.z + o.z};
  const double len = std::sqrt(dot(h, h));
  h = {h.x / len, h.y / len, h.z / len};
  const double rho = std::hypot(h.x, h.y);
  // The averages make c and i.h bitwise symmetric in (i, o) (they are equal mathematically).
  p.cos_d = 0.5 * (dot(i, h) + dot(o, h));
  p.sin_h = rho;
  if (!(rho > 0.0)) return false;
  const Dir3 a{h.x / rho, h.y / rho, 0.0};
  const double ia = dot(i, a), oa = dot(o, a);
  p.t_i = std::atan2(-ia, i.z);
  p.t_o = std::atan2(-oa, o.z);
  const double c_i = std::sqrt(ia * ia + i.z * i.z), c_o = std::sqrt(oa * oa + o.z * o.z);
  p.c = 0.5 * (c_i + c_o);
  p.sin_ti = -ia / c_i;
  p.cos_ti = i.z / c_i;
  p.sin_to = -oa / c_o;
  p.cos_to = o.z / c_o;
  // cos((t_i + t_o)/2) = cos(t_h) = h.n and cos((t_i - t_o)/2) = (i.h)/c (h bisects i_perp and o_perp).
  p.cos_half_sum = h.z;
  p.cos_half_diff = p.cos_d / p.c;
  return true;
}

// Fresnel along the 2D path: prod_j F(c |d_j . s_j|), the first facet `first`.
inline double fresnel_product(const FresnelFn& F, double t_i, double theta_m, FacetSide first, int k, double c) {
  if (!F) return 1.0;
  double dx = std::sin(t_i), dy = -std::cos(t_i);  // travel direction (into the groove)
  const double sm = std::sin(theta_m), cm = std::cos(theta_m);
  bool left = first == FacetSide::left;
  double prod = 1.0;
  for (int j = 0; j < k; ++j) {
    // Left facet normal at 2D angle -theta_m: (sin, cos); right at +theta_m: (-sin, cos).
    const double nx = left ? sm : -sm, ny = cm;
    const double dn = dx * nx + dy * ny;
    prod *= F(c * std::abs(dn));
    dx -= 2.0 * dn * nx;
    dy -= 2.0 * dn * ny;
    left = !left;
  }
  return prod;
}

// One facet-first path family of Eq. (5) in the cross-section, in the frame of the facet hit
// first (the right facet mirrored: t -> -t): a = the incident angle, b = (-1)^k times the exit
// angle, and their sines and cosines. Only the parity of k matters.
struct Ends {
  double a, b, sin_a, cos_a, sin_b, cos_b;
  double cos_half_diff, cos_half_sum;  // cos((a - b)/2), cos((a + b)/2)
};

inline Ends ends_of(const Plane& p, FacetSide side, int k) {
  const double sgn = (k % 2 == 0) ? 1.0 : -1.0;
  const double m = side == FacetSide::left ? 1.0 : -1.0;  // the mirror for the right facet
  Ends e;
  e.a = m * p.t_i;
  e.sin_a = m * p.sin_ti;
  e.cos_a = p.cos_ti;
  e.b = sgn * m * p.t_o;
  e.sin_b = sgn * m * p.sin_to;
  e.cos_b = p.cos_to;
  // a - b = m (t_i - sgn t_o): (a - b)/2 is +-(t_i - t_o)/2 or +-(t_i + t_o)/2, cos is even.
  e.cos_half_diff = sgn > 0.0 ? p.cos_half_diff : p.cos_half_sum;
  e.cos_half_sum = sgn > 0.0 ? p.cos_half_sum : p.cos_half_diff;
  return e;
}

// Whether the k-outcome can be non-empty (before any trigonometry): both rims lit, f_a > 0 and
// g_lo > 0 (theta_v > 2a and theta_v > -2b: upper > lower >= 0 needs both), and Eq. (4) gives
// K in {k, k + 1}, i.e. (k - 1) theta_v <= pi + 2a < (k + 1) theta_v, for the path and for its
// reverse (implied mathematically; both keep the test symmetric under i <-> o). Written with
// products instead of Eq. (4)'s floor of a quotient: the two differ only where the rounding of
// the boundary decides, and there the width vanishes (f(k) meets f_a or f_b).
inline bool outcome_possible(const Ends& e, double theta_v, int k) {
  if (!(theta_v > 2.0 * e.a && theta_v > -2.0 * e.b)) return false;
  const double span = std::numbers::pi + 2.0 * e.a, span_rev = std::numbers::pi - 2.0 * e.b;
  const double below = (k - 1) * theta_v, above = (k + 1) * theta_v;
  return below <= span && span < above && below <= span_rev && span_rev < above;
}

// The width G f_a of Eq. (6) (corrected, ERRATA E1) of the k-reflection outcome at the aperture
// theta_v, in the units of Eq. (6), for the path with ends e (theta_v solving Eq. 5 for them).
//
// Derivation. With f(theta) = sin(theta - a) the offset of the point at angle theta on the unit
// circle, Eq. (6) needs f_a = f(theta_v/2), f_b = max(0, f(-theta_v/2)) and f at the transition
// point theta_v (K - 1/2), K from Eq. (4); the k-outcome is [f_b, f_k] for K = k and [f_k, f_a]
// for K = k + 1. Eq. (5), k theta_v = a + pi - b + 2 pi j, turns the transition points into
//   f(theta_v (k - 1/2)) = sin(pi - b - theta_v/2) = sin(theta_v/2 + b) =: g_lo,
//   f(theta_v (k + 1/2)) = sin(pi - b + theta_v/2) = -sin(theta_v/2 - b) =: g_hi,
// and both cases of Eq. (6) are the one intersection (checked against G_kaleidoscopic in the tests)
//   W = min(f_a, g_lo) - max(0, f_b_raw, g_hi),   f_a = sin(theta_v/2 - a), f_b_raw = -sin(theta_v/2 + a),
// valid while K in {k, k + 1} (otherwise the k-th image of the opening wraps around the circle
// and the outcome is empty). The reversed path (o -> i) has a' = -b, b' = -a, the same theta_v
// and k, so its four offsets are these four, permuted: W is reciprocal term by term.
// Numerics: W is one sine (lower end 0) or a difference of two, upper = sin(theta_v/2 + p) with
// p in {-a, b} and lower = -sin(theta_v/2 + q) with q in {a, -b}; by sin x + sin y =
// 2 sin((x + y)/2) cos((x - y)/2) it is a product whose arguments are formed from the angles:
//   upper - lower = 2 sin(theta_v/2 + (p + q)/2) cos((p - q)/2), i.e.
//   f_a - f_b_raw = 2 sin(theta_v/2) cos(a),        g_lo - g_hi = 2 sin(theta_v/2) cos(b),
//   f_a - g_hi = 2 sin(theta_v/2 - (a + b)/2) cos((a - b)/2),
//   g_lo - f_b_raw = 2 sin(theta_v/2 + (a + b)/2) cos((a - b)/2),
// so that the width keeps its relative accuracy where the two ends nearly meet (the old
// f_k - f_b lost |f_k| / (f_k - f_b) ulps there, up to 3e-11 relative on random pairs), and the
// same operations on bitwise-swapped operands make rho(i, o) = rho(o, i) to the last bits.
// The min/max only choose the ends: their operands may carry rounding. (Remaining error: the
// rounding of theta_v, ~ulp(k pi) / k, lost once where the ends nearly meet; measured < 1e-12
// relative against long double, BeamWidthIsEq6.) Called only where outcome_possible holds.
//
// The evaluation is split in two so that a batch of solutions can take its sines together
// (brdf_3d_batch.cpp): beam_width_form chooses the ends and returns the width either as a value
// or as factor * sin(arg) with the argument formed from the angles; beam_width finishes it with
// std::sin. Both passes form the same arguments from the same operands.
struct WidthForm {
  double value = 0.0;   // the width when no sine is needed (before the clamp at 0)
  double arg = 0.0;     // otherwise the width is factor * sin(arg)
  double factor = 0.0;  // 1 or 2 cos((a - b)/2)
  bool needs_sine = false;
};
inline WidthForm beam_width_form(const Ends& e, double theta_v, double S, double C, int k) {
  const double f_a = S * e.cos_a - C * e.sin_a;      // sin(theta_v/2 - a)
  const double g_lo = S * e.cos_b + C * e.sin_b;     // sin(theta_v/2 + b)
  const double f_b = -(S * e.cos_a + C * e.sin_a);   // -sin(theta_v/2 + a)
  const double g_hi = -(S * e.cos_b - C * e.sin_b);  // -sin(theta_v/2 - b)
  const double lower = std::max(0.0, std::max(f_b, g_hi));
  const double half = 0.5 * theta_v;
  WidthForm w;
  if (k == 1) {
    // k = 1: theta_v = a - b + pi, so f_a = g_lo identically (the two upper ends coincide) and
    // every form reduces to the angles: f_a = sin((pi - a - b)/2) = cos((a + b)/2) (the 2D cosine
    // of incidence on the facet), f_a - f_b_raw = 2 S cos(a), g_lo - g_hi = 2 S cos(b). Choosing
    // between f_a and g_lo by their rounding would break the symmetry and the accuracy.
    if (!(std::min(f_a, g_lo) > lower)) return w;
    w.value = lower == 0.0 ? e.cos_half_sum : 2.0 * S * (f_b >= g_hi ? e.cos_a : e.cos_b);
    return w;
  }
  const bool upper_a = f_a <= g_lo;
  const double upper = upper_a ? f_a : g_lo;
  if (!(upper > lower)) return w;
  if (lower == 0.0) {
    w.needs_sine = true;
    w.factor = 1.0;
    w.arg = upper_a ? half - e.a : half + e.b;
  } else if (f_b >= g_hi) {  // the lower end is f_b_raw
    if (upper_a) {
      w.value = 2.0 * S * e.cos_a;
    } else {
      w.needs_sine = true;
      w.factor = 2.0 * e.cos_half_diff;
      w.arg = half + 0.5 * (e.a + e.b);
    }
  } else {  // the lower end is g_hi
    if (upper_a) {
      w.needs_sine = true;
      w.factor = 2.0 * e.cos_half_diff;
      w.arg = half - 0.5 * (e.a + e.b);
    } else {
      w.value = 2.0 * S * e.cos_b;
    }
  }
  return w;
}
// 2 sin(x) cos(y) = (2 cos(y)) sin(x) bitwise: the factor 2 is exact.
inline double beam_width(const Ends& e, double theta_v, double S, double C, int k) {
  const WidthForm w = beam_width_form(e, theta_v, S, C, k);
  return std::max(0.0, w.needs_sine ? w.factor * std::sin(w.arg) : w.value);
}

// D(theta_m) of analytic/ndf.cpp (same formulas, Walter et al. 2007, Sec. 5) from cos(theta_m)
// and sin(theta_m), which the caller has already: saves the two or three transcendental calls
// of D(ndf, theta_m, alpha) per solution. theta_m in [0, pi/2), so no chi+ test is needed.
inline double D_cs(NdfKind ndf, double c, double s, double alpha) {
  switch (ndf) {
    case NdfKind::ggx: {
      const double q = alpha * alpha * c * c + s * s;
      return alpha * alpha / (std::numbers::pi * q * q);
    }
    case NdfKind::beckmann: {
      const double t = s / c, c2 = c * c;
      return std::exp(-(t * t) / (alpha * alpha)) / (std::numbers::pi * alpha * alpha * c2 * c2);
    }
    case NdfKind::phong: {
      const double p = phong_exponent(alpha);
      return (p + 2.0) / (2.0 * std::numbers::pi) * std::pow(c, p);
    }
  }
  return 0.0;
}

// The term of Eq. (16) of one solution theta_v of Eq. (5) (0 when its outcome is empty).
inline double solution_term(const Plane& p, const Ends& e, FacetSide side, int k, double theta_v, double cos_i,
                            double cos_o, NdfKind ndf, double alpha, const FresnelFn& F) {
  if (!outcome_possible(e, theta_v, k)) return 0.0;
  const double half = 0.5 * theta_v;
  const double S = std::sin(half), C = std::cos(half);  // cos(theta_m), sin(theta_m)
  const double W = beam_width(e, theta_v, S, C, k);
  if (!(W > 0.0)) return 0.0;
  const double theta_m = 0.5 * (std::numbers::pi - theta_v);
  const double i_dot_s = p.c * W;  // |i.s| G = c G f_a: f_a is the 2D cosine of incidence
  // k = 1: s = h, so sin(theta_s)/sin(theta_h) = 1 exactly (Eq. 25); computing it would
  // divide two rounding errors next to the mirror direction.
  const double ratio = k == 1 ? 1.0 : C / (k * p.sin_h);
  // Lee et al. 2018, Eq. (16) with the Jacobian of Eq. (13).
  return ratio * fresnel_product(F, p.t_i, theta_m, side, k, p.c) * i_dot_s * D_cs(ndf, S, C, alpha) /
         (4.0 * p.cos_d * (cos_i * cos_o));
}

// The solutions of Eq. (5): theta_v = (a - b + (2 j + 1) pi) / k in (0, pi]. Written from a - b
// (bitwise the same for the reversed path) so that both directions find the same theta_v.
inline double solution(double a_minus_b, int j, int k) { return (a_minus_b + (2.0 * j + 1.0) * std::numbers::pi) / k; }

// Eq. (16) summed over k = k_lo..k_hi (k_lo >= 1) for a pair with the plane p: each solution's
// term on its own (brdf_3d.cpp), and the solutions in fixed slots without branches
// (brdf_3d_batch.cpp).
double brdf_per_solution(const Plane& p, double cos_i, double cos_o, int k_lo, int k_hi, NdfKind ndf, double alpha,
                         const FresnelFn& F);
double brdf_batched(const Plane& p, double cos_i, double cos_o, int k_lo, int k_hi, NdfKind ndf, double alpha,
                    const FresnelFn& F);

}  // namespace vgroove::analytic::brdf_terms
