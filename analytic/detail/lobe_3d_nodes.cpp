#include "vgroove/analytic/detail/lobe_3d_nodes.h"

#include "vgroove/analytic/detail/exp_log_batch.h"
#include "vgroove/analytic/detail/ndf_visit.h"
#include "vgroove/analytic/detail/sin_batch.h"
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

// floor x for x >= 0 (x + 2^52 - 2^52 rounds x to an integer, stepped down where it rounded up;
// x >= 2^52 is one already).
[[gnu::always_inline]] inline V floor_nonnegative(V x) {
  constexpr double two52 = 4503599627370496.0;
  const V r = (x + two52) - two52;
  const V f = r > x ? r - 1.0 : r;
  return x >= two52 ? x : f;
}

// piece_terms for one NDF (its formulas: ndf_visit.h).
template <typename Ndf>
[[gnu::always_inline]] inline void piece_terms_of(const Ndf& ndf, const Piece& p, int n, const double* v,
                                                  const double* rule_w, double* terms) {
  const V zero = splat(0.0), one = splat(1.0);
  const V st = splat(p.sin_tau), ct = splat(p.cos_tau);
  for (int b = 0; b < n; b += 4) {
    const V x = load(v + b);
    V cos_m, sin_m;
    if (p.in_w) {
      // groove_cdf_inverse_cos_sin at u = w^2 in (0, 1/2] (these nodes), with log(1 - u) =
      // log((1 - w)(1 + w)) by the polynomial where the NDF needs it.
      const V u = x * x;
      const V t = ndf.inverse_cdf(
          u, [&]() __attribute__((always_inline)) { return batch::log_batch((1.0 - x) * (1.0 + x)); });
      if constexpr (Ndf::kInverseGivesTan) {
        ndf_math::cos_sin_of_atan(t, cos_m, sin_m);
      } else {
        ndf_math::cos_sin_of_one_minus_cos(t, cos_m, sin_m);
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
    // The density: 2 w in w, 2 pi D cos sin in theta_m (D by the NDF's formula; exp and pow by
    // the polynomials, 0 below e^-708).
    const V density = p.in_w ? 2.0 * x : 2.0 * std::numbers::pi * ndf.D_cs(cos_m, sin_m) * cos_m * sin_m;
    store(terms + b, load(rule_w + b) * weight * density);
  }
}

// tail_strata for one NDF.
template <typename Ndf>
[[gnu::always_inline]] inline void tail_strata_of(const Ndf& ndf, const TailStrata& t, int n, const double* table,
                                                  double* theta_v, double* K, double* f_a, double* f_b, double* f_k,
                                                  double* w) {
  const V zero = splat(0.0);
  const V st = splat(t.sin_tau), ct = splat(t.cos_tau);
  const double span = std::numbers::pi + 2.0 * t.tf;
  for (int b = 0; b < n; b += 4) {
    // The half-aperture h = pi/2 - theta_m (cos theta_m = sin h, sin theta_m = cos h): h = asin of
    // cos theta_m or atan of cot theta_m, as the NDF's tail gives (tail_arg), by the Taylor series
    // to x^17 for x <= 0.1 (the next term is below 1e-19 relative; the tail's h <= pi / k_cap), the
    // library's asin / atan beyond.
    const V arg = ndf.tail_arg(ndf.tail_join(t.lead, load(table + b)));
    V cos_m, sin_m, h;
    const V z = arg * arg;
    if constexpr (Ndf::kTailArgIsCos) {
      cos_m = arg;
      sin_m = ndf_math::sqrt((1.0 - arg) * (1.0 + arg));
      const V pz = horner(z, 1.0 / 6, 3.0 / 40, 5.0 / 112, 35.0 / 1152, 63.0 / 2816, 231.0 / 13312, 143.0 / 10240,
                          6435.0 / 557056);
      h = arg + arg * (z * pz);
    } else {
      // cos theta_m = sin(atan x), sin theta_m = cos(atan x).
      ndf_math::cos_sin_of_atan(arg, sin_m, cos_m);
      const V pz = horner(z, -1.0 / 3, 1.0 / 5, -1.0 / 7, 1.0 / 9, -1.0 / 11, 1.0 / 13, -1.0 / 15, 1.0 / 17);
      h = arg + arg * (z * pz);
    }
    for (int l = 0; l < 4; ++l) {
      if (!(arg[l] <= 0.1)) h[l] = Ndf::kTailArgIsCos ? std::asin(arg[l]) : std::atan(arg[l]);
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

}  // namespace

// Both copies (common/simd.h) round as the scalar kernels.
VGROOVE_TARGET_CLONES
void piece_terms(const Piece& p, int n, const double* v, const double* rule_w, double* terms) {
  visit_ndf(
      p.ndf,
      p.alpha, [&](const auto& ndf) __attribute__((always_inline)) { piece_terms_of(ndf, p, n, v, rule_w, terms); });
}

VGROOVE_TARGET_CLONES
void tail_strata(const TailStrata& t, int n, const double* table, double* theta_v, double* K, double* f_a, double* f_b,
                 double* f_k, double* w) {
  visit_ndf(
      t.ndf, t.alpha, [&](const auto& ndf) __attribute__((always_inline)) {
        tail_strata_of(ndf, t, n, table, theta_v, K, f_a, f_b, f_k, w);
      });
}

}  // namespace vgroove::analytic::lobe_nodes
