#include "vgroove/analytic/lobe_3d_nodes.h"

#include "vgroove/analytic/brdf_3d.h"
#include "vgroove/analytic/exp_log_batch.h"
#include "vgroove/analytic/ndf.h"
#include "vgroove/analytic/sin_batch.h"
#include "vgroove/common/polynomial.h"
#include "vgroove/common/simd.h"

#include <cmath>
#include <numbers>

namespace vgroove::analytic::lobe_nodes {

namespace {

// Four doubles (common/simd.h); comparisons give masks, ?: selects lane by lane.
using V = simd::V4;
using simd::load;
using simd::splat;
using simd::store;

// Lane by lane: the correctly rounded square root, as std::sqrt (no errno here: -fno-math-errno).
[[gnu::always_inline]] inline V sqrt_v(V x) {
  return V{__builtin_sqrt(x[0]), __builtin_sqrt(x[1]), __builtin_sqrt(x[2]), __builtin_sqrt(x[3])};
}

// cos_sin_of_atan (brdf_3d.h) lane by lane: its two forms (t <= 1: c = 1 / sqrt(1 + t^2), s = t c;
// beyond: with m = 1 / t, s = 1 / sqrt(1 + m^2), c = m s) share one square root, on the selected m.
[[gnu::always_inline]] inline void cos_sin_of_atan_v(V t, V& c, V& s) {
  const auto low = t <= 1.0;
  const V m = low ? t : 1.0 / t;
  const V q = 1.0 / sqrt_v(1.0 + m * m), a = m * q;
  c = low ? q : a;
  s = low ? a : q;
}

// floor x for x >= 0 (x + 2^52 - 2^52 rounds x to an integer, stepped down where it rounded up;
// x >= 2^52 is one already).
[[gnu::always_inline]] inline V floor_nonnegative(V x) {
  constexpr double two52 = 4503599627370496.0;
  const V r = (x + two52) - two52;
  const V f = r > x ? r - 1.0 : r;
  return x >= two52 ? x : f;
}

}  // namespace

// Both copies (common/simd.h) round as the scalar kernels.
VGROOVE_TARGET_CLONES
void piece_terms(const Piece& p, int n, const double* v, const double* rule_w, double* terms) {
  const bool ggx = p.ndf == NdfKind::ggx;
  const double phong_p = p.ndf == NdfKind::phong ? phong_exponent(p.alpha) : 0.0;
  const V zero = splat(0.0), one = splat(1.0);
  const V st = splat(p.sin_tau), ct = splat(p.cos_tau);
  for (int b = 0; b < n; b += 4) {
    const V x = load(v + b);
    V cos_m, sin_m;
    if (p.in_w && ggx) {
      // groove_cdf_inverse_cos_sin for GGX: tan theta_m = alpha sqrt(u / (1 - u)), then
      // cos_sin_of_atan's two forms (t <= 1 and beyond), selected.
      const V u = x * x;
      cos_sin_of_atan_v(splat(p.alpha) * sqrt_v(u / (1.0 - u)), cos_m, sin_m);
    } else if (p.in_w) {
      // groove_cdf_inverse_cos_sin for Beckmann and Phong, with log(1 - u) = log((1 - w)(1 + w))
      // and expm1 by the polynomials (u = w^2 in (0, 1/2] at these nodes).
      const V log_1mu = batch::log_batch((1.0 - x) * (1.0 + x));
      if (p.ndf == NdfKind::phong) {
        // 1 - cos theta_m = -expm1(log(1 - u) / (p + 2)).
        const V one_minus_cos = -batch::expm1_batch(log_1mu / (phong_p + 2.0));
        cos_m = 1.0 - one_minus_cos;
        sin_m = sqrt_v(one_minus_cos * (2.0 - one_minus_cos));
      } else {
        // tan theta_m = alpha sqrt(-log(1 - u)), then cos_sin_of_atan as for GGX.
        cos_sin_of_atan_v(splat(p.alpha) * sqrt_v(-log_1mu), cos_m, sin_m);
      }
    } else {
      sin_cos_quadrant(x, sin_m, cos_m);
    }
    V fk;
    if (p.in_w) {
      // weight_piece: f_k = Im(z^(2K-1)) cos tf - Re(z^(2K-1)) sin tf, z = sin_m + i cos_m, the
      // power by squaring (K is the piece's: the same steps in every lane).
      V re = one, im = zero, br = sin_m, bi = cos_m;
      for (unsigned e = static_cast<unsigned>(2 * p.K - 1);; e >>= 1) {
        if (e & 1u) {
          const V t = re * br - im * bi;
          im = re * bi + im * br;
          re = t;
        }
        if (e <= 1u) break;
        const V t = br * br - bi * bi;
        bi = 2.0 * br * bi;
        br = t;
      }
      fk = im * ct - re * st;
    } else {
      // At nodes in theta_m the angle is at hand: f_k = sin((K - 1/2) theta_v - tf) =
      // -sin(a), a = (K - 1/2) theta_v - tf - pi in (tf - theta_v/2, tf + theta_v/2] by Eq. (4)
      // (lobe_3d.cpp, f_k_of), theta_v = pi - 2 theta_m: one polynomial sine instead of the power.
      const V a = (p.K - 0.5) * (std::numbers::pi - 2.0 * x) - p.tf - std::numbers::pi;
      const auto neg = a < 0.0;
      const V sa = sin_full(neg ? -a : a);
      fk = -(neg ? -sa : sa);
    }
    const V f_a = cos_m * ct - sin_m * st;
    const V nb = -(cos_m * ct + sin_m * st);
    const V f_b = zero < nb ? nb : zero;                   // std::max(0.0, nb)
    const V f_k = fk < f_b ? f_b : (f_a < fk ? f_a : fk);  // std::clamp(fk, f_b, f_a)
    const V Gf = p.K == p.k ? f_k - f_b : f_a - f_k;
    const V w = Gf / (2.0 * cos_m * ct);
    const V weight = f_a > 0.0 ? w : zero;
    V density;
    if (p.in_w) {
      density = 2.0 * x;
    } else {
      V D;
      if (ggx) {
        // D_cs_ggx: alpha^2 / (pi q^2), q = alpha^2 cos^2 + sin^2.
        const V q = p.alpha * p.alpha * cos_m * cos_m + sin_m * sin_m;
        D = p.alpha * p.alpha / (std::numbers::pi * q * q);
      } else if (p.ndf == NdfKind::beckmann) {
        // D_cs: exp(-tan^2 / alpha^2) / (pi alpha^2 cos^4), the exponential by the polynomial (0
        // below e^-708).
        const V t = sin_m / cos_m, c2 = cos_m * cos_m;
        const V z = -(t * t) / (p.alpha * p.alpha);
        const V e = batch::exp_batch(z >= -708.0 ? z : zero);
        D = (z >= -708.0 ? e : zero) / (std::numbers::pi * p.alpha * p.alpha * c2 * c2);
      } else {
        // D_cs: (p + 2) / (2 pi) cos^p = e^(p log cos) by the polynomials (0 below e^-708; cos
        // theta_m at a node is a normal number, and p log cos stays far below 709).
        const double ph = phong_p;
        if (ph == 0.0) {
          D = splat((ph + 2.0) / (2.0 * std::numbers::pi));  // alpha = 1: cos^0 = 1 (exp_batch(0) is 1 too)
        } else {
          const V z = ph * batch::log_batch(cos_m);
          const V e = batch::exp_batch(z >= -708.0 ? (z <= 709.0 ? z : splat(709.0)) : zero);
          D = (ph + 2.0) / (2.0 * std::numbers::pi) * (z >= -708.0 ? e : zero);
        }
      }
      density = 2.0 * std::numbers::pi * D * cos_m * sin_m;
    }
    store(terms + b, load(rule_w + b) * weight * density);
  }
}

VGROOVE_TARGET_CLONES
void tail_strata(const TailStrata& t, int n, const double* table, double* theta_v, double* K, double* f_a, double* f_b,
                 double* f_k, double* w) {
  const V zero = splat(0.0);
  const V st = splat(t.sin_tau), ct = splat(t.cos_tau);
  const double span = std::numbers::pi + 2.0 * t.tf;
  for (int b = 0; b < n; b += 4) {
    const V entry = load(table + b);
    // The half-aperture h = pi/2 - theta_m (cos theta_m = sin h, sin theta_m = cos h): h = asin of
    // cos theta_m (Phong) or atan of cot theta_m (GGX: sqrt((1 - u) / u) / alpha, Beckmann
    // 1 / (alpha sqrt(-log(1 - u)))), by the Taylor series to x^17 for x <= 0.1 (the next term is
    // below 1e-19 relative; the tail's h <= pi / k_cap), the library's asin / atan beyond.
    V cos_m, sin_m, h, arg;
    const bool phong = t.ndf == NdfKind::phong;
    if (phong) {
      const V c = t.lead * entry;
      cos_m = c;
      sin_m = sqrt_v((1.0 - c) * (1.0 + c));
      arg = c;
      const V z = c * c;
      const V pz = horner(z, 1.0 / 6, 3.0 / 40, 5.0 / 112, 35.0 / 1152, 63.0 / 2816, 231.0 / 13312, 143.0 / 10240,
                          6435.0 / 557056);
      h = c + c * (z * pz);
    } else {
      V x;
      if (t.ndf == NdfKind::ggx) {
        const V one_minus_u = t.lead * entry;
        x = sqrt_v(one_minus_u / (1.0 - one_minus_u)) / t.alpha;
      } else {
        x = 1.0 / (t.alpha * sqrt_v(-(t.lead + entry)));
      }
      // cos theta_m = sin(atan x), sin theta_m = cos(atan x).
      cos_sin_of_atan_v(x, sin_m, cos_m);
      arg = x;
      const V z = x * x;
      const V pz = horner(z, -1.0 / 3, 1.0 / 5, -1.0 / 7, 1.0 / 9, -1.0 / 11, 1.0 / 13, -1.0 / 15, 1.0 / 17);
      h = x + x * (z * pz);
    }
    for (int l = 0; l < 4; ++l) {
      if (!(arg[l] <= 0.1)) h[l] = phong ? std::asin(arg[l]) : std::atan(arg[l]);
    }
    const V tv = 2.0 * h;
    const V fa = cos_m * ct - sin_m * st;
    const V nb = -(cos_m * ct + sin_m * st);
    const V fb = zero < nb ? nb : zero;  // std::max(0.0, nb)
    // Eq. (4): K = floor(span / theta_v) + 1, saturated at INT_MAX (kaleidoscope.h, saturate_to_int).
    const V k1 = floor_nonnegative(span / tv) + 1.0;
    const V Kd = k1 < 2147483647.0 ? k1 : splat(2147483647.0);
    // f_k_of: -sin((K - 1/2) theta_v - tf - pi), the sine odd-extended (lobe_3d.cpp, sin_pi).
    const V a = (Kd - 0.5) * tv - t.tf - std::numbers::pi;
    const auto neg = a < 0.0;
    const V sa = sin_full(neg ? -a : a);
    const V fk = -(neg ? -sa : sa);
    const V fk_clamped = fk < fb ? fb : (fa < fk ? fa : fk);  // std::clamp(fk, fb, fa)
    store(theta_v + b, tv);
    store(K + b, Kd);
    store(f_a + b, fa);
    store(f_b + b, fb);
    store(f_k + b, fk_clamped);
    store(w + b, 2.0 * cos_m * t.cos_tau);
  }
}

}  // namespace vgroove::analytic::lobe_nodes
