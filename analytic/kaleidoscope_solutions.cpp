#include "vgroove/analytic/kaleidoscope_solutions.h"

#include <algorithm>
#include <cmath>

namespace vgroove::analytic {

CrossSection cross_section(double t_i, double t_o) {
  CrossSection p;
  p.t_i = t_i;
  p.t_o = t_o;
  p.sin_ti = std::sin(t_i);
  p.cos_ti = std::cos(t_i);
  p.sin_to = std::sin(t_o);
  p.cos_to = std::cos(t_o);
  p.cos_half_sum = std::cos(0.5 * (t_i + t_o));
  p.cos_half_diff = std::cos(0.5 * (t_i - t_o));
  p.sin_half_sum = std::abs(std::sin(0.5 * (t_i + t_o)));
  p.single_from_h = p.cos_half_sum < kGrazingHalfVector;
  return p;
}

Ends ends_of(const CrossSection& p, FacetSide side, int k) {
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

// Both rims lit, f_a > 0 and g_lo > 0 (theta_v > 2a and theta_v > -2b: upper > lower >= 0 needs
// both), and Eq. (4) gives K in {k, k + 1}, i.e. (k - 1) theta_v <= pi + 2a < (k + 1) theta_v, for
// the path and for its reverse (implied mathematically; both keep the test symmetric under
// i <-> o). Written with products instead of Eq. (4)'s floor of a quotient: the two differ only
// where the rounding of the boundary decides, and there the width vanishes (f(k) meets f_a or f_b).
bool outcome_possible(const Ends& e, double theta_v, int k) {
  if (!(theta_v > 2.0 * e.a && theta_v > -2.0 * e.b)) return false;
  const double span = std::numbers::pi + 2.0 * e.a, span_rev = std::numbers::pi - 2.0 * e.b;
  const double below = (k - 1) * theta_v, above = (k + 1) * theta_v;
  return below <= span && span < above && below <= span_rev && span_rev < above;
}

// Numerics (the header gives the derivation): W is one sine (lower end 0) or a difference of two,
// upper = sin(theta_v/2 + p) with p in {-a, b} and lower = -sin(theta_v/2 + q) with q in {a, -b};
//   f_a - f_b_raw = 2 sin(theta_v/2) cos(a),        g_lo - g_hi = 2 sin(theta_v/2) cos(b),
//   f_a - g_hi = 2 sin(theta_v/2 - (a + b)/2) cos((a - b)/2),
//   g_lo - f_b_raw = 2 sin(theta_v/2 + (a + b)/2) cos((a - b)/2),
// so that the width keeps its relative accuracy where the two ends nearly meet, and the same
// operations on bitwise-swapped operands make rho(i, o) = rho(o, i) to the last bits.
// Which ends hold is read from the offsets themselves where they are far apart. Each offset is a
// sum of two products of numbers below 1 with a few ulp of error, and theta_v/2's rounding moves
// it by at most ulp(pi) / k: within kEndsTie of each other (or of 0) their comparison may be
// decided by rounding. There (and where the width itself is below kEndsTie) the width is the
// smallest of the differences upper - lower over every pair of ends, each written as a product:
// min(f_a, g_lo) - max(0, f_b_raw, g_hi) is exactly that minimum, and it needs no comparison of
// rounded offsets. Near the horizon the offsets are 1 - O(1e-16) while the width is a product of
// two cosines of the order of 1e-8 each: the comparisons there said nothing (Brdf3d.GrazingPairs*).
// (Remaining error: the rounding of theta_v, ~ulp(k pi) / k, lost once where the ends nearly
// meet; measured < 1e-12 relative against long double, BeamWidthIsEq6.)
namespace {

constexpr double kEndsTie = 1e-14;

// min(f_a, g_lo) - max(0, f_b_raw, g_hi) as the smallest of its six differences, each a product.
double width_from_every_pair(const Ends& e, double half, double S) {
  const double ab2 = 0.5 * (e.a + e.b);
  const double d[6] = {
      std::sin(half - e.a),                          // f_a - 0
      std::sin(half + e.b),                          // g_lo - 0
      2.0 * S * e.cos_a,                             // f_a - f_b_raw
      2.0 * S * e.cos_b,                             // g_lo - g_hi
      2.0 * std::sin(half - ab2) * e.cos_half_diff,  // f_a - g_hi
      2.0 * std::sin(half + ab2) * e.cos_half_diff,  // g_lo - f_b_raw
  };
  // The order of the operands of each min is the same for the reversed path's permutation.
  const double w = std::min(std::min(std::min(d[0], d[1]), std::min(d[2], d[3])), std::min(d[4], d[5]));
  return std::max(0.0, w);
}

}  // namespace

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
    // between f_a and g_lo by their rounding would break the symmetry and the accuracy; the
    // width is the smallest of the three (the pairs' differences, as above), with a tie of the
    // lower ends decided by the products, not by the offsets.
    const double top = std::min(f_a, g_lo);
    const bool clear =
        top - lower > kEndsTie && (lower == 0.0 ? std::max(f_b, g_hi) < -kEndsTie : std::abs(f_b - g_hi) > kEndsTie);
    if (clear) {
      w = lower == 0.0 ? e.cos_half_sum : 2.0 * S * (f_b >= g_hi ? e.cos_a : e.cos_b);
    } else {
      w = std::min(e.cos_half_sum, 2.0 * S * std::min(e.cos_a, e.cos_b));
    }
    return std::max(0.0, w);
  }
  const bool upper_a = f_a <= g_lo;
  const double upper = upper_a ? f_a : g_lo;
  const bool clear =
      upper - lower > kEndsTie && std::abs(f_a - g_lo) > kEndsTie &&
      (lower == 0.0 ? std::max(f_b, g_hi) < -kEndsTie : std::abs(f_b - g_hi) > kEndsTie && lower > kEndsTie);
  if (!clear) return width_from_every_pair(e, half, S);
  if (lower == 0.0) {
    w = upper_a ? std::sin(half - e.a) : std::sin(half + e.b);
  } else if (f_b >= g_hi) {  // the lower end is f_b_raw
    w = upper_a ? 2.0 * S * e.cos_a : 2.0 * std::sin(half + 0.5 * (e.a + e.b)) * e.cos_half_diff;
  } else {  // the lower end is g_hi
    w = upper_a ? 2.0 * std::sin(half - 0.5 * (e.a + e.b)) * e.cos_half_diff : 2.0 * S * e.cos_b;
  }
  return std::max(0.0, w);
}

}  // namespace vgroove::analytic
