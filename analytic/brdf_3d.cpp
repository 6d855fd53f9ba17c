#include "vgroove/analytic/brdf_3d.h"

#include "vgroove/analytic/kaleidoscope.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <numbers>

namespace vgroove::analytic {

Dir3 dir3(double theta, double phi) {
  return {std::sin(theta) * std::cos(phi), std::sin(theta) * std::sin(phi), std::cos(theta)};
}

namespace {

double dot(const Dir3& a, const Dir3& b) { return a.x * b.x + a.y * b.y + a.z * b.z; }

// The cross-section of the groove that holds h: the 2D angles of i, o and h, and c = |i_perp|.
// Every field is computed symmetrically in (i, o) or swaps with them bitwise (t_i <-> t_o, ...),
// so that the evaluation below is reciprocal to the last bit (see beam_width).
struct Plane {
  double t_i = 0.0, t_o = 0.0, t_h = 0.0;
  double c = 1.0;      // sqrt(1 - (i.u)^2) = sqrt(1 - (o.u)^2): the length of i's projection
  double sin_h = 0.0;  // sin(theta_h)
  double cos_d = 1.0;  // i.h = o.h
  double sin_ti = 0.0, cos_ti = 1.0, sin_to = 0.0, cos_to = 1.0;
  double cos_half_sum = 1.0;   // cos((t_i + t_o)/2)
  double cos_half_diff = 1.0;  // cos((t_i - t_o)/2)
};

// h = (i + o)/|i + o|, a = the horizontal direction of h, so that t_h = -theta_h <= 0 and the
// facet with normal h is the "left" one (2D angle -theta_m). Returns false when h = n exactly.
bool make_plane(const Dir3& i, const Dir3& o, Plane& p) {
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
  p.t_h = -std::atan2(rho, h.z);
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
double fresnel_product(const FresnelFn& F, double t_i, double theta_m, FacetSide first, int k, double c) {
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

Ends ends_of(const Plane& p, FacetSide side, int k) {
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
bool outcome_possible(const Ends& e, double theta_v, int k) {
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
double beam_width(const Ends& e, double theta_v, double S, double C, int k) {
  const double f_a = S * e.cos_a - C * e.sin_a;      // sin(theta_v/2 - a)
  const double g_lo = S * e.cos_b + C * e.sin_b;     // sin(theta_v/2 + b)
  const double f_b = -(S * e.cos_a + C * e.sin_a);   // -sin(theta_v/2 + a)
  const double g_hi = -(S * e.cos_b - C * e.sin_b);  // -sin(theta_v/2 - b)
  const double lower = std::max(0.0, std::max(f_b, g_hi));
  const double half = 0.5 * theta_v;
  double w;
  if (k == 1) {
    // k = 1: theta_v = a - b + pi, so f_a = g_lo identically (the two upper ends coincide) and
    // every form reduces to the angles: f_a = sin((pi - a - b)/2) = cos((a + b)/2) (the 2D cosine
    // of incidence on the facet), f_a - f_b_raw = 2 S cos(a), g_lo - g_hi = 2 S cos(b). Choosing
    // between f_a and g_lo by their rounding would break the symmetry and the accuracy.
    if (!(std::min(f_a, g_lo) > lower)) return 0.0;
    if (lower == 0.0) {
      w = e.cos_half_sum;
    } else {
      w = 2.0 * S * (f_b >= g_hi ? e.cos_a : e.cos_b);
    }
    return std::max(0.0, w);
  }
  const bool upper_a = f_a <= g_lo;
  const double upper = upper_a ? f_a : g_lo;
  if (!(upper > lower)) return 0.0;
  if (lower == 0.0) {
    w = upper_a ? std::sin(half - e.a) : std::sin(half + e.b);
  } else if (f_b >= g_hi) {  // the lower end is f_b_raw
    w = upper_a ? 2.0 * S * e.cos_a : 2.0 * std::sin(half + 0.5 * (e.a + e.b)) * e.cos_half_diff;
  } else {  // the lower end is g_hi
    w = upper_a ? 2.0 * std::sin(half - 0.5 * (e.a + e.b)) * e.cos_half_diff : 2.0 * S * e.cos_b;
  }
  return std::max(0.0, w);
}

// D(theta_m) of analytic/ndf.cpp (same formulas, Walter et al. 2007, Sec. 5) from cos(theta_m)
// and sin(theta_m), which the caller has already: saves the two or three transcendental calls
// of D(ndf, theta_m, alpha) per solution. theta_m in [0, pi/2), so no chi+ test is needed.
double D_cs(NdfKind ndf, double c, double s, double alpha) {
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
double solution_term(const Plane& p, const Ends& e, FacetSide side, int k, double theta_v, double cos_i, double cos_o,
                     NdfKind ndf, double alpha, const FresnelFn& F) {
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
double solution(double a_minus_b, int j, int k) { return (a_minus_b + (2.0 * j + 1.0) * std::numbers::pi) / k; }

// Eq. (16) for one k, straightforwardly: every j with theta_v in (0, pi], both facets.
double brdf_k_every_j(const Plane& p, double cos_i, double cos_o, int k, NdfKind ndf, double alpha,
                      const FresnelFn& F) {
  double sum = 0.0;
  for (FacetSide side : {FacetSide::left, FacetSide::right}) {
    // k = 1: s = h is the left facet by the choice of a (t_h <= 0); the right facet's solution
    // theta_m = -theta_h exists only as the rounding image of theta_h = 0.
    if (k == 1 && side == FacetSide::right) continue;
    const Ends e = ends_of(p, side, k);
    const double d = e.a - e.b;
    const int j_lo = static_cast<int>(std::ceil((-d - std::numbers::pi) / (2.0 * std::numbers::pi)));
    const int j_hi =
        static_cast<int>(std::floor((k * std::numbers::pi - d - std::numbers::pi) / (2.0 * std::numbers::pi)));
    for (int j = j_lo; j <= j_hi; ++j) {
      const double theta_v = solution(d, j, k);
      if (!(theta_v > 0.0 && theta_v <= std::numbers::pi)) continue;
      sum += solution_term(p, e, side, k, theta_v, cos_i, cos_o, ndf, alpha, F);
    }
  }
  return sum;
}

// Eq. (16) summed over k = k_lo..k_hi in one pass over the solutions that can exist.
// For one facet and one parity of k the ends (a, b) are fixed, and theta_v = X / k with
// X = a - b + (2 j + 1) pi. Eq. (4) allows the k-outcome only for K in {k, k + 1}, i.e.
//   (k - 1) X <= k span < (k + 1) X,   span = pi + 2a   <=>   k |X - span| <= X (up to the ends),
// and theta_v <= pi needs k >= X / pi. With X - span = 2 pi j - (a + b) and |a + b| < pi, only
// j = 0 can meet both (|X - span| <= X / k <= pi), and then k runs over [X / pi, X / |a + b|]:
// a handful of k for most (i, o), all of them only near a = -b (the path equal to its reverse).
// So the pass visits the solutions that exist plus O(1) others, whatever max_k is; the j = +-1
// and one k beyond each end are visited too, against rounding (outcome_possible decides, as in
// brdf_k_every_j, so both sum the same terms).
double brdf_single_pass(const Plane& p, double cos_i, double cos_o, int k_lo, int k_hi, NdfKind ndf, double alpha,
                        const FresnelFn& F) {
  double sum = 0.0;
  for (FacetSide side : {FacetSide::left, FacetSide::right}) {
    for (int k_first : {1, 2}) {
      const Ends e = ends_of(p, side, k_first);  // depends on the parity of k only
      const double d = e.a - e.b;
      const double span = std::numbers::pi + 2.0 * e.a;
      for (int j = -1; j <= 1; ++j) {
        const double X = d + (2.0 * j + 1.0) * std::numbers::pi;
        if (!(X > 0.0)) continue;
        const double dev = std::abs(X - span);
        // In double until clamped: X / dev may exceed any int.
        const double k_top = dev > 0.0 ? std::floor(X / dev) + 1.0 : static_cast<double>(k_hi);
        const int k_end = static_cast<int>(std::min(static_cast<double>(k_hi), k_top));
        int k = std::max(k_lo, static_cast<int>(std::ceil(X / std::numbers::pi)) - 1);
        if (k < 1) k = 1;
        if ((k - k_first) % 2 != 0) ++k;  // the parity of this pass
        for (; k <= k_end; k += 2) {
          // k = 1: s = h is the left facet (as in brdf_k_every_j).
          if (k == 1 && side == FacetSide::right) continue;
          const double theta_v = solution(d, j, k);
          if (!(theta_v > 0.0 && theta_v <= std::numbers::pi)) continue;
          sum += solution_term(p, e, side, k, theta_v, cos_i, cos_o, ndf, alpha, F);
        }
      }
    }
  }
  return sum;
}

double ct_at(const Dir3& i, const Dir3& o, NdfKind ndf, double alpha, const FresnelFn& F) {
  const double cos_i = i.z, cos_o = o.z;
  if (!(cos_i > 0.0 && cos_o > 0.0)) return 0.0;
  Dir3 h{i.x + o.x, i.y + o.y, i.z + o.z};
  const double len = std::sqrt(dot(h, h));
  h = {h.x / len, h.y / len, h.z / len};
  const double theta_h = std::atan2(std::hypot(h.x, h.y), h.z);
  const double ih = dot(i, h), oh = dot(o, h);
  // Lee et al. 2018, Eq. (3) with the V-cavity G1 of Eq. (2).
  const double G = std::min(G1_vcavity(ih, cos_i, h.z), G1_vcavity(oh, cos_o, h.z));
  const double Fr = F ? F(ih) : 1.0;
  // Lee et al. 2018, Eq. (1).
  return Fr * D(ndf, theta_h, alpha) * G / (4.0 * cos_i * cos_o);
}

double brdf_range(const Dir3& i, const Dir3& o, int k_lo, int k_hi, NdfKind ndf, double alpha, const FresnelFn& F,
                  bool reference = false) {
  const double cos_i = i.z, cos_o = o.z;
  // Below or at the horizon: no flux (a set of measure zero; see the header).
  if (!(cos_i > 0.0 && cos_o > 0.0)) return 0.0;
  Plane p;
  if (!make_plane(i, o, p)) {
    // h = n: the limit of Eq. (16) is Cook-Torrance with G = 1 for k = 1 (sin theta_s / sin theta_h
    // -> 1) and diverges like 1 / sin(theta_h) for k >= 2.
    if (k_hi >= 2) return std::numeric_limits<double>::infinity();
    return k_lo <= 1 ? ct_at(i, o, ndf, alpha, F) : 0.0;
  }
  if (!reference) return brdf_single_pass(p, cos_i, cos_o, std::max(1, k_lo), k_hi, ndf, alpha, F);
  double sum = 0.0;
  for (int k = std::max(1, k_lo); k <= k_hi; ++k) sum += brdf_k_every_j(p, cos_i, cos_o, k, ndf, alpha, F);
  return sum;
}

}  // namespace

double beam_width_k(double t_i, double t_o, double theta_v, int k, FacetSide first) {
  Plane p;
  p.t_i = t_i;
  p.t_o = t_o;
  p.sin_ti = std::sin(t_i);
  p.cos_ti = std::cos(t_i);
  p.sin_to = std::sin(t_o);
  p.cos_to = std::cos(t_o);
  p.cos_half_sum = std::cos(0.5 * (t_i + t_o));
  p.cos_half_diff = std::cos(0.5 * (t_i - t_o));
  const Ends e = ends_of(p, first, k);
  if (!outcome_possible(e, theta_v, k)) return 0.0;
  return beam_width(e, theta_v, std::sin(0.5 * theta_v), std::cos(0.5 * theta_v), k);
}

double vgroove_brdf_k_reference(const Dir3& i, const Dir3& o, int k, NdfKind ndf, double alpha) {
  return brdf_range(i, o, k, k, ndf, alpha, FresnelFn{}, true);
}
double vgroove_brdf_reference(const Dir3& i, const Dir3& o, NdfKind ndf, double alpha, int max_k) {
  return brdf_range(i, o, 1, max_k, ndf, alpha, FresnelFn{}, true);
}

double vgroove_brdf_k(const Dir3& i, const Dir3& o, int k, NdfKind ndf, double alpha) {
  return brdf_range(i, o, k, k, ndf, alpha, FresnelFn{});
}
double vgroove_brdf_k(const Dir3& i, const Dir3& o, int k, NdfKind ndf, double alpha, const FresnelFn& F) {
  return brdf_range(i, o, k, k, ndf, alpha, F);
}
double vgroove_brdf(const Dir3& i, const Dir3& o, NdfKind ndf, double alpha, int max_k) {
  return brdf_range(i, o, 1, max_k, ndf, alpha, FresnelFn{});
}
double vgroove_brdf(const Dir3& i, const Dir3& o, NdfKind ndf, double alpha, int max_k, const FresnelFn& F) {
  return brdf_range(i, o, 1, max_k, ndf, alpha, F);
}
double cook_torrance(const Dir3& i, const Dir3& o, NdfKind ndf, double alpha) {
  return ct_at(i, o, ndf, alpha, FresnelFn{});
}
double cook_torrance(const Dir3& i, const Dir3& o, NdfKind ndf, double alpha, const FresnelFn& F) {
  return ct_at(i, o, ndf, alpha, F);
}

double groove_cdf(NdfKind ndf, double alpha, double theta_m) {
  if (!(theta_m > 0.0)) return 0.0;
  if (!(theta_m < 0.5 * std::numbers::pi)) return 1.0;
  const double t = std::tan(theta_m), t2 = t * t;
  switch (ndf) {
    case NdfKind::ggx:
      return t2 / (alpha * alpha + t2);
    case NdfKind::beckmann:
      return -std::expm1(-t2 / (alpha * alpha));
    case NdfKind::phong: {
      // 1 - cos^(p+2), p + 2 = 2 / alpha^2; log cos = log1p(-2 sin^2(theta/2)) keeps small angles exact.
      const double s = std::sin(0.5 * theta_m);
      return -std::expm1((phong_exponent(alpha) + 2.0) * std::log1p(-2.0 * s * s));
    }
  }
  return 0.0;
}

double groove_cdf_inverse(NdfKind ndf, double alpha, double u) {
  if (!(u > 0.0)) return 0.0;
  if (!(u < 1.0)) return 0.5 * std::numbers::pi;
  switch (ndf) {
    case NdfKind::ggx:
      return std::atan(alpha * std::sqrt(u / (1.0 - u)));
    case NdfKind::beckmann:
      return std::atan(alpha * std::sqrt(-std::log1p(-u)));
    case NdfKind::phong: {
      const double one_minus_cos = -std::expm1(std::log1p(-u) / (phong_exponent(alpha) + 2.0));
      return 2.0 * std::asin(std::sqrt(0.5 * one_minus_cos));
    }
  }
  return 0.0;
}

}  // namespace vgroove::analytic
