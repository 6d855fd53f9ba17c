// vgroove analytic: e^z and log x for four doubles at a time, by polynomials that vectorize (GCC
// and clang vector extensions): Beckmann's exponential in the batched BRDF pass
// (brdf_3d_batch.cpp), Beckmann's and Phong's D at the lobe's quadrature nodes (lobe_3d_nodes.cpp).
// exp_batch(z), z in [-708, 709]: Cody-Waite reduction and a degree-13 series; log_batch(x), x a
// positive normal number: 2 atanh(s) to s^25. Outside the range the lanes are meaningless.
// Accuracy against long double: exp within 0.97 ulp, expm1 within 1.91 ulp, log within 1.93 ulp;
// Beckmann's batched BRDF values within 2.5e-14 relative of std::exp's. Always inlined.
// Tests: tests/analytic/exp_log_batch_test.cpp (ExpLogBatch.ExpWithinTwoUlpOverItsRange,
// ExpLogBatch.Expm1WithinTwoUlpOverItsRange, ExpLogBatch.LogWithinTwoUlpOfItsValue),
// tests/analytic/brdf_3d_test.cpp (Brdf3d.BeckmannVectorPassIsWithinItsBoundOrDeclines).
// Derivation: docs/derivations/numerics.md.
#pragma once

#include "vgroove/common/polynomial.h"
#include "vgroove/common/simd.h"

#include <cstdint>

#if defined(__GNUC__) && !defined(__clang__)
#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wpsabi"  // common/simd.h
#endif

namespace vgroove::analytic::batch {

using simd::I4;
using simd::V4;

// The reduction z = k ln 2 + r shared by exp_batch and expm1_batch: returns e^r - 1 =
// r + r^2 P(r), and 2^k in two_k.
[[gnu::always_inline]] inline V4 expm1_reduced(V4 z, V4& two_k) {
  constexpr double round_const = 6755399441055744.0;  // 1.5 2^52: (x + c) - c rounds x to an integer
  const V4 rc = V4{round_const, round_const, round_const, round_const};
  const V4 shifted = z * 1.44269504088896338700e+00 + round_const;
  const V4 kd = shifted - round_const;
  const V4 r = (z - kd * 6.93147180369123816490e-01) - kd * 1.90821492927058770002e-10;
  const V4 r2 = r * r;
  // 1/2! + r/3! + ... + r^11/13!.
  const V4 P = estrin(r, 5.000000000000000000000000e-01, 1.666666666666666666666667e-01, 4.166666666666666666666667e-02,
                      8.333333333333333333333333e-03, 1.388888888888888888888889e-03, 1.984126984126984126984127e-04,
                      2.480158730158730158730159e-05, 2.755731922398589065255732e-06, 2.755731922398589065255732e-07,
                      2.505210838544171877505211e-08, 2.087675698786809897921009e-09, 1.605904383682161459939238e-10);
  // k from the bits of k + 1.5 2^52 (same exponent as the constant), then 2^k = (k + 1023) << 52.
  const I4 k = reinterpret_cast<I4>(shifted) - reinterpret_cast<I4>(rc);
  two_k = reinterpret_cast<V4>((k + 1023) << 52);
  return r + r2 * P;
}

[[gnu::always_inline]] inline V4 exp_batch(V4 z) {
  V4 two_k;
  const V4 s = expm1_reduced(z, two_k);
  return (1.0 + s) * two_k;
}

// e^z - 1 for z in [-708, 709]: 2^k (e^r - 1) + (2^k - 1), the series without its leading 1 (no
// cancellation however small z is: k = 0 leaves the series alone) and 2^k - 1 exact for
// -53 <= k <= 53 (beyond, the result is 2^k e^r or -1 to rounding).
[[gnu::always_inline]] inline V4 expm1_batch(V4 z) {
  V4 two_k;
  const V4 s = expm1_reduced(z, two_k);
  return two_k * s + (two_k - 1.0);
}

[[gnu::always_inline]] inline V4 log_batch(V4 x) {
  const I4 bits = reinterpret_cast<I4>(x);
  // m in [1, 2) from the mantissa; the exponent field as a double (its bits in the mantissa of
  // 2^52, less 2^52 and the bias); above sqrt(2), m halved and e raised.
  V4 m = reinterpret_cast<V4>((bits & 0x000fffffffffffffLL) | 0x3ff0000000000000LL);
  V4 e = reinterpret_cast<V4>(((bits >> 52) & 0x7ffLL) | 0x4330000000000000LL) - (4503599627370496.0 + 1023.0);
  const auto high = m > 1.41421356237309504880;
  m = high ? 0.5 * m : m;
  e = high ? e + 1.0 : e;
  const V4 s = (m - 1.0) / (m + 1.0), s2 = s * s;
  // 1/3 + s^2/5 + ... + s^22/25.
  const V4 P = estrin(s2, 1.0 / 3, 1.0 / 5, 1.0 / 7, 1.0 / 9, 1.0 / 11, 1.0 / 13, 1.0 / 15, 1.0 / 17, 1.0 / 19,
                      1.0 / 21, 1.0 / 23, 1.0 / 25);
  const V4 log_m = 2.0 * s + 2.0 * s * (s2 * P);
  return e * 6.93147180369123816490e-01 + (log_m + e * 1.90821492927058770002e-10);
}

}  // namespace vgroove::analytic::batch

#if defined(__GNUC__) && !defined(__clang__)
#pragma GCC diagnostic pop
#endif
