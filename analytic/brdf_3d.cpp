#include "vgroove/analytic/brdf_3d.h"

#include "vgroove/analytic/kaleidoscope.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>

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

// The outcome of exactly k reflections of Eq. (6) for the rays aimed at `first`, or G = 0.
struct KShare {
  double G = 0.0;  // fraction of the facet's lit width f_a
  double f_a = 0.0;
  double theta_o = 0.0;  // 2D exit angle
};
KShare share_k(double t_i, double theta_v, FacetSide first, int k) {
  const FacetPrediction p = G_kaleidoscopic(t_i, theta_v, first);
  KShare s;
  if (!p.lit) return s;
  s.f_a = p.f_a;
  if (p.fewer.n == k) {
    s.G = p.fewer.G;
    s.theta_o = p.fewer.theta_o;
  } else if (p.more.n == k) {
    s.G = p.more.G;
    s.theta_o = p.more.theta_o;
  }
  return s;
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
  const double span = M_PI + 2.0 * e.a, span_rev = M_PI - 2.0 * e.b;
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
      return alpha * alpha / (M_PI * q * q);
    }
    case NdfKind::beckmann: {
      const double t = s / c, c2 = c * c;
      return std::exp(-(t * t) / (alpha * alpha)) / (M_PI * alpha * alpha * c2 * c2);
    }
    case NdfKind::phong: {
      const double p = phong_exponent(alpha);
      return (p + 2.0) / (2.0 * M_PI) * std::pow(c, p);
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
  const double theta_m = 0.5 * (M_PI - theta_v);
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
double solution(double a_minus_b, int j, int k) { return (a_minus_b + (2.0 * j + 1.0) * M_PI) / k; }

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
    const int j_lo = static_cast<int>(std::ceil((-d - M_PI) / (2.0 * M_PI)));
    const int j_hi = static_cast<int>(std::floor((k * M_PI - d - M_PI) / (2.0 * M_PI)));
    for (int j = j_lo; j <= j_hi; ++j) {
      const double theta_v = solution(d, j, k);
      if (!(theta_v > 0.0 && theta_v <= M_PI)) continue;
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
      const double span = M_PI + 2.0 * e.a;
      for (int j = -1; j <= 1; ++j) {
        const double X = d + (2.0 * j + 1.0) * M_PI;
        if (!(X > 0.0)) continue;
        const double dev = std::abs(X - span);
        // In double until clamped: X / dev may exceed any int.
        const double k_top = dev > 0.0 ? std::floor(X / dev) + 1.0 : static_cast<double>(k_hi);
        const int k_end = static_cast<int>(std::min(static_cast<double>(k_hi), k_top));
        int k = std::max(k_lo, static_cast<int>(std::ceil(X / M_PI)) - 1);
        if (k < 1) k = 1;
        if ((k - k_first) % 2 != 0) ++k;  // the parity of this pass
        for (; k <= k_end; k += 2) {
          // k = 1: s = h is the left facet (as in brdf_k_every_j).
          if (k == 1 && side == FacetSide::right) continue;
          const double theta_v = solution(d, j, k);
          if (!(theta_v > 0.0 && theta_v <= M_PI)) continue;
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
  if (!(theta_m < 0.5 * M_PI)) return 1.0;
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
  if (!(u < 1.0)) return 0.5 * M_PI;
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

// ------------------------------------------------------------------------------------------
// The lobes: push-forward of the groove distribution.
namespace {

// Gauss-Legendre nodes and weights of order n on [-1, 1] (Newton on P_n).
void gauss_legendre(int n, std::vector<double>& x, std::vector<double>& w) {
  x.assign(n, 0.0);
  w.assign(n, 0.0);
  for (int i = 0; i < n; ++i) {
    double z = std::cos(M_PI * (i + 0.75) / (n + 0.5));
    double dp = 1.0;
    for (int it = 0; it < 100; ++it) {
      double p0 = 1.0, p1 = z;
      for (int j = 2; j <= n; ++j) {
        const double p2 = ((2.0 * j - 1.0) * z * p1 - (j - 1.0) * p0) / j;
        p0 = p1;
        p1 = p2;
      }
      if (n == 1) p0 = 1.0;
      dp = n * (z * p1 - p0) / (z * z - 1.0);
      const double dz = p1 / dp;
      z -= dz;
      if (std::abs(dz) < 1e-16) break;
    }
    x[i] = -z;
    w[i] = 2.0 / ((1.0 - z * z) * dp * dp);
  }
}

// The rules used per piece (orders 2, 4, 8), computed once.
struct GlRule {
  std::vector<double> x, w;
  explicit GlRule(int n) { gauss_legendre(n, x, w); }
};
const GlRule& gl_rule(int n) {
  static const GlRule r2(2), r4(4), r8(8);
  return n == 2 ? r2 : (n == 4 ? r4 : r8);
}

enum class LobeModel { vgroove, cook_torrance };

struct LobeRun {
  NdfKind ndf;
  double alpha;
  double theta_i;
  int tb, pb, max_k;
  LobeModel model;
  std::vector<double>* acc;  // where the deposits go: [row][t][p], as Lobe3d::hist_by_k
};

// One groove azimuth: the geometry of the cross-section.
struct Azimuth {
  double tau;     // projected incident angle t_i
  double iu;      // i.u
  double c;       // sqrt(1 - iu^2)
  double ca, sa;  // cos, sin phi_a
};

// The bin of the 2D exit angle t in the cross-section, or -1 below the horizon.
int bin_of(const LobeRun& r, const Azimuth& az, double t) {
  // o = c (-sin t a + cos t n) - iu u, a = (ca, sa, 0), u = (-sa, ca, 0).
  const double ox = -az.c * std::sin(t) * az.ca + az.iu * az.sa;
  const double oy = -az.c * std::sin(t) * az.sa - az.iu * az.ca;
  const double oz = az.c * std::cos(t);
  if (!(oz > 0.0)) return -1;
  const double theta = std::atan2(std::hypot(ox, oy), oz);
  const double dphi = 2.0 * M_PI / r.pb;
  int tb = static_cast<int>(theta / (0.5 * M_PI / r.tb));
  tb = std::min(tb, r.tb - 1);
  int p = static_cast<int>(std::floor((std::atan2(oy, ox) + 0.5 * dphi) / dphi));
  p = ((p % r.pb) + r.pb) % r.pb;
  return tb * r.pb + p;
}

// The 2D exit angles at which the arc of exits crosses a bin edge (theta_o edges, the horizon
// and the phi_o lines), all in (-pi/2, pi/2] (escaping exits have cos t > 0).
void edge_crossings(const LobeRun& r, const Azimuth& az, std::vector<double>& T) {
  T.clear();
  T.push_back(-0.5 * M_PI);
  T.push_back(0.5 * M_PI);
  for (int b = 1; b < r.tb; ++b) {
    // o_z = c cos t = cos(theta_b).
    const double q = std::cos(b * 0.5 * M_PI / r.tb) / az.c;
    if (q < 1.0) {
      const double t = std::acos(q);
      T.push_back(t);
      T.push_back(-t);
    }
  }
  const double dphi = 2.0 * M_PI / r.pb;
  for (int p = 0; p < r.pb / 2; ++p) {
    // o on the line at azimuth phi_b: c sin t sin(phi_a - phi_b) = -(i.u) cos(phi_a - phi_b).
    const double d = std::atan2(az.sa, az.ca) - (p + 0.5) * dphi;
    const double den = az.c * std::sin(d);
    if (den == 0.0) continue;
    const double v = -az.iu * std::cos(d) / den;
    if (std::abs(v) < 1.0) T.push_back(std::asin(v));
  }
  std::sort(T.begin(), T.end());
}

// The weight P(theta_v) per unit CDF and the exit angle for one facet and k.
struct Outcome {
  double P = 0.0;
  double t_o = 0.0;
};
Outcome outcome_ct(const Azimuth& az, FacetSide side, double theta_v, double w);
Outcome outcome(const LobeRun& r, const Azimuth& az, FacetSide side, int k, double theta_v) {
  Outcome res;
  const double w = opening_width(az.tau, theta_v);
  if (!(w > 0.0)) return res;
  if (r.model == LobeModel::vgroove) {
    const KShare s = share_k(az.tau, theta_v, side, k);
    res.P = s.G * s.f_a / w;
    res.t_o = s.theta_o;
    return res;
  }
  return outcome_ct(az, side, theta_v, w);
}

// The same weight without the exit angle, inlined for the quadrature nodes: Eq. (4) and the
// corrected Eq. (6) for the facet with the (mirrored) projected angle tf (see kaleidoscope.cpp).
double weight_k(const LobeRun& r, const Azimuth& az, FacetSide side, int k, double theta_v) {
  if (r.model == LobeModel::cook_torrance) return outcome(r, az, side, k, theta_v).P;
  const double tf = side == FacetSide::left ? az.tau : -az.tau;
  const double f_a = std::sin(0.5 * theta_v - tf);
  if (!(f_a > 0.0)) return 0.0;
  const double f_b = std::max(0.0, -std::sin(0.5 * theta_v + tf));
  const int K = saturate_to_int(std::floor((M_PI + 2.0 * tf) / theta_v) + 1.0);
  if (K != k && K != k + 1) return 0.0;
  const double f_k = std::clamp(std::sin(K * theta_v - 0.5 * theta_v - tf), f_b, f_a);
  const double Gf = K == k ? f_k - f_b : f_a - f_k;  // G f_a of the k-reflection outcome
  return Gf / (2.0 * std::sin(0.5 * theta_v) * std::cos(az.tau));
}

Outcome outcome_ct(const Azimuth& az, FacetSide side, double theta_v, double w) {
  Outcome res;
  // Cook-Torrance: one reflection off the facet, V-cavity G = min(G1(i), G1(o)) in the
  // cross-section (the ratios of Eq. (2) are invariant under the projection).
  const double theta_m = 0.5 * (M_PI - theta_v);
  const double t_s = side == FacetSide::left ? -theta_m : theta_m;
  const double f_a = std::cos(az.tau - t_s);
  if (!(f_a > 0.0)) return res;
  const double t_o = std::remainder(2.0 * t_s - az.tau, 2.0 * M_PI);
  const double G = std::min(G1_vcavity_inplane(az.tau, t_s), G1_vcavity_inplane(t_o, t_s));
  res.P = G * f_a / w;
  res.t_o = t_o;
  return res;
}

// Which branch of the V-cavity min is active (for the Cook-Torrance breakpoints).
int ct_branch(const Azimuth& az, FacetSide side, double theta_v) {
  const double theta_m = 0.5 * (M_PI - theta_v);
  const double t_s = side == FacetSide::left ? -theta_m : theta_m;
  const double t_o = 2.0 * t_s - az.tau;
  const double gi = 2.0 * std::cos(t_s) * std::cos(az.tau) / std::abs(std::cos(az.tau - t_s));
  const double go = 2.0 * std::cos(t_s) * std::cos(t_o) / std::abs(std::cos(t_o - t_s));
  if (gi >= 1.0 && go >= 1.0) return 0;
  return gi < go ? 1 : 2;
}

struct Scratch {
  std::vector<double> T, X;
  double band_total = 0.0;                      // flux deposited by the bands at this node
  std::vector<std::pair<size_t, double>> tail;  // the tail's deposits at this node
};

// Integrate one facet's k-reflection outcomes over theta_v in [x_lo, x_hi] with the weight
// `weight` (the phi_a quadrature weight), depositing into the bins (and their mirror images).
void integrate_band(const LobeRun& r, const Azimuth& az, FacetSide side, int k, double x_lo, double x_hi, double weight,
                    Scratch& sc) {
  if (!(x_hi > x_lo)) return;
  const double tf = side == FacetSide::left ? az.tau : -az.tau;
  std::vector<double>& X = sc.X;
  X.clear();
  X.push_back(x_lo);
  X.push_back(x_hi);
  auto add = [&](double x) {
    if (x > x_lo && x < x_hi) X.push_back(x);
  };
  // Where Eq. (4) or (6) change form: lit (theta_v = 2 tf), f_b clamp (theta_v = -2 tf), K changes
  // ((pi + 2 tf) / j), the f_k clamp at psi = 0 ((pi + tf) / (j - 1/2)).
  add(2.0 * tf);
  add(-2.0 * tf);
  for (int j = std::max(1, k - 1); j <= k + 2; ++j) {
    add((M_PI + 2.0 * tf) / j);
    add((M_PI + tf) / (j - 0.5));
  }
  // Where the exit crosses a bin edge: t = sigma (-1)^k (tf + pi - k theta_v) (mod 2 pi),
  // sigma = +1 for the left facet, -1 for the right (its mirror image).
  const int kk = r.model == LobeModel::vgroove ? k : 1;
  const double sgn = ((kk % 2 == 0) ? 1.0 : -1.0) * (side == FacetSide::left ? 1.0 : -1.0);
  // v = tf + pi - k theta_v sweeps [v_lo, v_hi]; t = sgn (v - 2 pi j) must lie in (-pi/2, pi/2],
  // so only the sorted crossings inside each window sgn [v_lo - 2 pi j, v_hi - 2 pi j] matter.
  const double v_lo = tf + M_PI - kk * x_hi, v_hi = tf + M_PI - kk * x_lo;
  const int jj_lo = static_cast<int>(std::floor((v_lo - 0.5 * M_PI) / (2.0 * M_PI)));
  const int jj_hi = static_cast<int>(std::ceil((v_hi + 0.5 * M_PI) / (2.0 * M_PI)));
  for (int j = jj_lo; j <= jj_hi; ++j) {
    const double a = sgn * (v_lo - 2.0 * M_PI * j), b = sgn * (v_hi - 2.0 * M_PI * j);
    const auto first = std::lower_bound(sc.T.begin(), sc.T.end(), std::min(a, b));
    const auto last = std::upper_bound(sc.T.begin(), sc.T.end(), std::max(a, b));
    for (auto it = first; it != last; ++it) add((tf + M_PI - sgn * *it - 2.0 * M_PI * j) / kk);
  }
  std::sort(X.begin(), X.end());
  if (r.model == LobeModel::cook_torrance) {
    // The V-cavity min switches branch: located by scanning and bisection.
    const size_t n0 = X.size();
    for (size_t s = 0; s + 1 < n0; ++s) {
      const int m = 16;
      for (int q = 0; q < m; ++q) {
        double a = X[s] + (X[s + 1] - X[s]) * q / m, b = X[s] + (X[s + 1] - X[s]) * (q + 1) / m;
        const int ba = ct_branch(az, side, a), bb = ct_branch(az, side, b);
        if (ba == bb) continue;
        for (int it = 0; it < 60; ++it) {
          const double mid = 0.5 * (a + b);
          (ct_branch(az, side, mid) == ba ? a : b) = mid;
        }
        X.push_back(0.5 * (a + b));
      }
    }
    std::sort(X.begin(), X.end());
  }
  const int row = std::min(k, r.max_k + 1);
  std::vector<double>& acc = *r.acc;
  for (size_t s = 0; s + 1 < X.size(); ++s) {
    const double x0 = X[s], x1 = X[s + 1];
    if (!(x1 > x0)) continue;
    const Outcome mid = outcome(r, az, side, k, 0.5 * (x0 + x1));
    if (!(mid.P > 0.0)) continue;
    const int bin = bin_of(r, az, mid.t_o);
    if (bin < 0) continue;
    // The weight is dCDF(theta_m) = 2 pi D cos sin d theta_m. Near theta_m = 0, where D peaks
    // (width alpha), Gauss-Legendre runs in w = sqrt(CDF) (du = 2 w dw, theta_m(w) analytic at
    // w = 0); above the median in theta_m itself, since theta_m(w) is singular at w = 1 (sqrt for
    // GGX, log for Beckmann). Pieces are cut to at most 0.05 in w or theta_m.
    const double m0 = 0.5 * (M_PI - x1), m1 = 0.5 * (M_PI - x0);
    const double m_half = groove_cdf_inverse(r.ndf, r.alpha, 0.5);
    double val = 0.0;
    auto gl_pieces = [&](double a0, double a1, bool in_w) {
      if (!(a1 > a0)) return;
      // In theta_m also at most a ratio 1.25 per piece: D's tail above the median falls off on the
      // scale of theta_m itself (a power law for GGX, faster for Beckmann and Phong).
      const double len = in_w ? 0.05 : std::min(0.05, 0.25 * a0);
      const int pieces = static_cast<int>(std::ceil((a1 - a0) / len));
      for (int pc = 0; pc < pieces; ++pc) {
        const double b0 = a0 + (a1 - a0) * pc / pieces, b1 = a0 + (a1 - a0) * (pc + 1) / pieces;
        const double mass_est = in_w ? (b1 - b0) * (b1 + b0) : 1.0;
        // Order by the piece's mass: pieces lighter than 1e-9 (narrow bands of high k) are short.
        const GlRule& rule = gl_rule(mass_est < 1e-9 ? 2 : (mass_est < 1e-6 ? 4 : 8));
        double sum = 0.0;
        for (size_t q = 0; q < rule.x.size(); ++q) {
          const double v = 0.5 * (b0 + b1) + 0.5 * (b1 - b0) * rule.x[q];
          if (in_w) {
            const double theta_v = M_PI - 2.0 * groove_cdf_inverse(r.ndf, r.alpha, v * v);
            sum += rule.w[q] * weight_k(r, az, side, k, theta_v) * 2.0 * v;
          } else {
            const double pdf = 2.0 * M_PI * D(r.ndf, v, r.alpha) * std::cos(v) * std::sin(v);
            sum += rule.w[q] * weight_k(r, az, side, k, M_PI - 2.0 * v) * pdf;
          }
        }
        val += 0.5 * (b1 - b0) * sum;
      }
    };
    if (m0 < m_half) {
      gl_pieces(std::sqrt(groove_cdf(r.ndf, r.alpha, m0)), std::sqrt(groove_cdf(r.ndf, r.alpha, std::min(m1, m_half))),
                true);
    }
    if (m1 > m_half) gl_pieces(std::max(m0, m_half), m1, false);
    val *= weight;
    const int t = bin / r.pb, p = bin % r.pb;
    // The mirror image pi - phi_a of the groove (y -> -y) sends the same flux to phi_o -> -phi_o.
    acc[(static_cast<size_t>(row) * r.tb + t) * r.pb + p] += val;
    acc[(static_cast<size_t>(row) * r.tb + t) * r.pb + (r.pb - p) % r.pb] += val;
    sc.band_total += 2.0 * val;
  }
}

// The tail beyond the explicit bands: midpoint rule in the CDF.
// The outcomes of more than k_cap reflections come from theta_v < span / k_cap (Eq. 4).
void integrate_tail(const LobeRun& r, const Azimuth& az, FacetSide side, int k_cap, int n, double weight, Scratch& sc) {
  const double tf = side == FacetSide::left ? az.tau : -az.tau;
  const double u0 = groove_cdf(r.ndf, r.alpha, 0.5 * (M_PI - (M_PI + 2.0 * tf) / k_cap));
  const double mass = 1.0 - u0;
  if (!(mass > 0.0)) return;
  for (int q = 0; q < n; ++q) {
    const double u = u0 + mass * (q + 0.5) / n;
    const double theta_v = M_PI - 2.0 * groove_cdf_inverse(r.ndf, r.alpha, u);
    const FacetPrediction p = G_kaleidoscopic(az.tau, theta_v, side);
    if (!p.lit) continue;
    const double w = opening_width(az.tau, theta_v);
    for (const BounceShare& b : {p.fewer, p.more}) {
      if (!(b.G > 0.0) || b.n <= k_cap) continue;
      const int bin = bin_of(r, az, b.theta_o);
      if (bin < 0) continue;
      const int row = std::min(b.n, r.max_k + 1);
      const int t = bin / r.pb, pp = bin % r.pb;
      const double val = weight * mass / n * b.G * p.f_a / w;
      sc.tail.emplace_back((static_cast<size_t>(row) * r.tb + t) * r.pb + pp, val);
      sc.tail.emplace_back((static_cast<size_t>(row) * r.tb + t) * r.pb + (r.pb - pp) % r.pb, val);
    }
  }
}

Lobe3d run_lobe(NdfKind ndf, double alpha, double theta_i, int theta_bins, int phi_bins, int max_k, LobeModel model,
                const Lobe3dOptions& opt) {
  Lobe3d L;
  L.theta_bins = theta_bins;
  L.phi_bins = phi_bins;
  L.max_k = max_k;
  const int rows = max_k + 2;
  L.by_k.assign(rows, 0.0);
  L.hist.assign(static_cast<size_t>(theta_bins) * phi_bins, 0.0);
  L.hist_by_k.assign(static_cast<size_t>(rows) * theta_bins * phi_bins, 0.0);
  LobeRun r{ndf, alpha, theta_i, theta_bins, phi_bins, max_k, model, &L.hist_by_k};
  std::vector<double> gx, gw;
  gauss_legendre(opt.phi_order, gx, gw);
  Scratch sc;
  // The light at i = dir3(theta_i, pi): i.a = -sin(theta_i) cos(phi_a), i.u = sin(theta_i) sin(phi_a).
  const double si = std::sin(theta_i), ci = std::cos(theta_i);
  // k beyond which the bands stop and the tail takes over.
  const int k_cap = std::max(opt.k_bands, max_k + 1);
  // The deposits of the grooves at azimuth phi_a (and pi - phi_a) with the quadrature weight
  // dphi, into *r.acc.
  auto node = [&](double phi_a, double dphi) {
    // Area fraction 2 D cos sin d theta_m d phi_a = (1/pi) dCDF d phi_a; phi_a in [0, pi/2] and
    // its mirror image pi - phi_a (y -> -y) cover [0, pi).
    const double weight = dphi / M_PI;
    Azimuth az;
    az.ca = std::cos(phi_a);
    az.sa = std::sin(phi_a);
    az.tau = std::atan2(si * az.ca, ci);
    az.iu = si * az.sa;
    az.c = std::sqrt(std::max(0.0, 1.0 - az.iu * az.iu));
    edge_crossings(r, az, sc.T);
    sc.band_total = 0.0;
    sc.tail.clear();
    for (FacetSide side : {FacetSide::left, FacetSide::right}) {
      const double tf = side == FacetSide::left ? az.tau : -az.tau;
      const double span = M_PI + 2.0 * tf;  // Eq. (4): K = floor(span / theta_v) + 1
      if (model == LobeModel::cook_torrance) {
        integrate_band(r, az, side, 1, 0.0, M_PI, weight, sc);
        continue;
      }
      int k = 1;
      for (;; ++k) {
        // K in {k, k + 1} <=> theta_v in [span / (k + 1), span / (k - 1)).
        const double x_lo = span / (k + 1), x_hi = k == 1 ? M_PI : std::min(M_PI, span / (k - 1));
        integrate_band(r, az, side, k, x_lo, x_hi, weight, sc);
        if (k >= k_cap) break;
        // Stop once the grooves with outcomes beyond k (theta_v < span / k) weigh nothing.
        if (k >= max_k + 1 && 1.0 - groove_cdf(ndf, alpha, 0.5 * (M_PI - span / k)) < 1e-16) break;
      }
      if (k >= k_cap) integrate_tail(r, az, side, k_cap, opt.tail_strata, weight, sc);
    }
    // The tail's total is known exactly: each groove sends all its flux somewhere (Eq. 6 over both
    // facets sums to 1), so the tail carries 2 weight - band_total. The midpoint rule only
    // distributes it.
    double tail_total = 0.0;
    for (const auto& d : sc.tail) tail_total += d.second;
    const double scale = tail_total > 0.0 ? (2.0 * weight - sc.band_total) / tail_total : 0.0;
    std::vector<double>& acc = *r.acc;
    for (const auto& d : sc.tail) acc[d.first] += scale * d.second;
  };
  // The phi_a quadrature: Gauss-Legendre panels between cuts at the points where the per-bin
  // integrands are not smooth.
  //  - Square-root points: where c(phi_a) = cos(theta_b) a theta_o edge starts to cut the arc of
  //    exits (at t = 0, its crossings move like sqrt(phi_a - phi*)). The pieces next to them are
  //    mapped by phi = phi0 + (phi1 - phi0) g(s), g with a zero slope at each such end (s^2,
  //    1 - (1 - s)^2 or the smoothstep s^2 (3 - 2 s)), which turns sqrt into smooth.
  //  - Kinks at the bin corners (corner_cuts): where the arc passes through a corner o_c the bin's
  //    integrand changes slope (on one side the arc cuts the corner over a length ~ |phi_a - phi*|,
  //    on the other it misses the bin). The arcs of the groove at phi_a lie on the circle
  //    o.u = -i.u, i.e. i + o lies in the cross-section (a, n), so phi* is the azimuth of i + o_c,
  //    folded into [0, pi/2] (the mirror image pi - phi_a serves the mirror corner). These were
  //    the largest error of the lobe: a fixed rule of step h leaves ~|slope jump| h^2 at each
  //    (measured 7e-6 per bin at 384 panels, GGX 0.5 at 30 deg, back-scattering plane).
  // Remaining kinks (an arc's end or a change of form of Eq. 4/6 crossing a bin edge) are weaker.
  std::vector<std::pair<double, bool>> cuts{{0.0, false}, {0.5 * M_PI, false}};  // (phi_a, sqrt point)
  for (int b = 1; b < theta_bins; ++b) {
    const double sb = std::sin(b * 0.5 * M_PI / theta_bins);
    if (sb < si) cuts.emplace_back(std::asin(sb / si), true);
  }
  if (opt.corner_cuts) {
    const Dir3 i = dir3(theta_i, M_PI);
    for (int b = 1; b <= theta_bins; ++b) {
      for (int q = 0; q < phi_bins; ++q) {
        const Dir3 o_c = dir3(b * 0.5 * M_PI / theta_bins, (q + 0.5) * 2.0 * M_PI / phi_bins);
        double phi = std::atan2(i.y + o_c.y, i.x + o_c.x);
        if (phi < 0.0) phi += M_PI;
        if (phi > 0.5 * M_PI) phi = M_PI - phi;
        if (phi > 0.0 && phi < 0.5 * M_PI) cuts.emplace_back(phi, false);
      }
    }
  }
  std::sort(cuts.begin(), cuts.end());
  // Merge coincident cuts (a sqrt point wins).
  std::vector<std::pair<double, bool>> merged;
  for (const auto& c : cuts) {
    if (!merged.empty() && c.first - merged.back().first < 1e-12) {
      merged.back().second = merged.back().second || c.second;
    } else {
      merged.push_back(c);
    }
  }
  for (size_t c = 0; c + 1 < merged.size(); ++c) {
    const double p0 = merged[c].first, p1 = merged[c + 1].first;
    const bool sq0 = merged[c].second, sq1 = merged[c + 1].second;
    if (!(p1 > p0)) continue;
    // The map g(s) and g'(s) of the piece.
    auto map = [&](double sv, double& g, double& dg) {
      if (sq0 && sq1) {
        g = sv * sv * (3.0 - 2.0 * sv);
        dg = 6.0 * sv * (1.0 - sv);
      } else if (sq0) {
        g = sv * sv;
        dg = 2.0 * sv;
      } else if (sq1) {
        g = 1.0 - (1.0 - sv) * (1.0 - sv);
        dg = 2.0 * (1.0 - sv);
      } else {
        g = sv;
        dg = 1.0;
      }
    };
    const int np_rounded = static_cast<int>(std::lround(opt.phi_panels * (p1 - p0) / (0.5 * M_PI)));
    if (np_rounded == 0 && !sq0 && !sq1) {
      // A piece shorter than half a panel (between close corner cuts): the midpoint rule; its
      // O(len^3 f'') is far below the kinks' errors at these lengths.
      node(0.5 * (p0 + p1), p1 - p0);
      continue;
    }
    const int np = std::max(1, np_rounded);
    for (int pn = 0; pn < np; ++pn) {
      for (int q = 0; q < opt.phi_order; ++q) {
        const double sv = (pn + 0.5 + 0.5 * gx[q]) / np;
        double g, dg;
        map(sv, g, dg);
        node(p0 + (p1 - p0) * g, (p1 - p0) * dg * 0.5 * gw[q] / np);
      }
    }
  }
  for (int row = 0; row < rows; ++row) {
    for (int t = 0; t < theta_bins; ++t) {
      for (int p = 0; p < phi_bins; ++p) {
        const double v = L.hist_by_k[(static_cast<size_t>(row) * theta_bins + t) * phi_bins + p];
        L.by_k[row] += v;
        L.hist[static_cast<size_t>(t) * phi_bins + p] += v;
      }
    }
    L.albedo += L.by_k[row];
  }
  return L;
}

}  // namespace

Lobe3d vgroove_lobe_3d(NdfKind ndf, double alpha, double theta_i, int theta_bins, int phi_bins, int max_k) {
  return vgroove_lobe_3d(ndf, alpha, theta_i, theta_bins, phi_bins, max_k, Lobe3dOptions{});
}
Lobe3d vgroove_lobe_3d(NdfKind ndf, double alpha, double theta_i, int theta_bins, int phi_bins, int max_k,
                       const Lobe3dOptions& opt) {
  return run_lobe(ndf, alpha, theta_i, theta_bins, phi_bins, max_k, LobeModel::vgroove, opt);
}
Lobe3d cook_torrance_lobe_3d(NdfKind ndf, double alpha, double theta_i, int theta_bins, int phi_bins) {
  return cook_torrance_lobe_3d(ndf, alpha, theta_i, theta_bins, phi_bins, Lobe3dOptions{});
}
Lobe3d cook_torrance_lobe_3d(NdfKind ndf, double alpha, double theta_i, int theta_bins, int phi_bins,
                             const Lobe3dOptions& opt) {
  return run_lobe(ndf, alpha, theta_i, theta_bins, phi_bins, 1, LobeModel::cook_torrance, opt);
}

}  // namespace vgroove::analytic
