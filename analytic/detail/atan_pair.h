// vgroove analytic: atan2(y, x) of two pairs at once, x >= 0 (the groove frame's incident and exit
// angles, brdf_3d.cpp), by a table and a short series that vectorize (SSE2, two lanes).
//
// q = min(|y|, x) / max(|y|, x) in [0, 1] and c = j / 8 its nearest eighth (j = 0..8); by the
// addition formula atan q = atan c + atan r, r = (q - c) / (1 + q c), |r| <= 1/16 (q - c is exact:
// c / 2 <= q <= 2 c for j >= 1). atan r = r + r (r^2 P(r^2)), P the Taylor coefficients
// -1/3, 1/5, ..., 1/13: the first term left out, r^15 / 15, is below 1e-18 of r. Where |y| > x,
// atan2 = pi/2 - atan q = atan(1 / c) - atan r. The table holds atan(j / 8) and atan(8 / j) each as
// a double and its remainder, so the sum rounds once, at the end: hi + (lo +- atan r); the sign
// of y is then put on the result (atan2(-0, x) = -0).
//
// Accuracy: within 3 ulp of the correctly rounded value (2.5 measured: q rounds to half an ulp
// of q, and atan q may lie in the binade below q's), equal to it in 87 % of arguments
// (tests/analytic/atan_pair_test.cpp, against long double); not bit for bit std::atan2.
// Not defined for x < 0, or x = y = 0.
#pragma once

#include "vgroove/common/polynomial.h"
#include "vgroove/common/simd.h"

#include <cstdint>

namespace vgroove::analytic {

using Double2 = simd::V2;

namespace atan_pair_detail {

// atan(j / 8) for j = 0..8, then atan(8 / j) (pi/2 for j = 0): value and remainder (mpmath, 200 bits).
inline constexpr double kHi[18] = {0.0,
                                   0.12435499454676144,
                                   0.24497866312686414,
                                   0.35877067027057225,
                                   0.46364760900080609,
                                   0.55859931534356244,
                                   0.64350110879328437,
                                   0.71882999962162453,
                                   0.78539816339744828,
                                   1.5707963267948966,
                                   1.4464413322481351,
                                   1.3258176636680326,
                                   1.2120256565243244,
                                   1.1071487177940904,
                                   1.0121970114513341,
                                   0.92729521800161219,
                                   0.85196632717327214,
                                   0.78539816339744828};
inline constexpr double kLo[18] = {0.0,
                                   -3.1253241424539383e-18,
                                   1.0698755618734451e-17,
                                   -2.4623815582638635e-17,
                                   2.2698777452961687e-17,
                                   -5.4556305485916264e-18,
                                   1.5834785051444286e-17,
                                   -2.1478388444456983e-17,
                                   3.061616997868383e-17,
                                   6.123233995736766e-17,
                                   9.2113239715450516e-17,
                                   -8.8244293739511363e-17,
                                   3.0345004308748468e-17,
                                   9.4044713735663794e-17,
                                   6.6687970505959288e-17,
                                   4.5397554905923374e-17,
                                   -2.8311574060691011e-17,
                                   3.061616997868383e-17};

}  // namespace atan_pair_detail

// {atan2(y[0], x[0]), atan2(y[1], x[1])} for x >= 0.
inline Double2 atan2_pair(Double2 y, Double2 x) {
  using Int2 = simd::I2;
  const Int2 sign_bit = {INT64_MIN, INT64_MIN};
  const Double2 n = reinterpret_cast<Double2>(reinterpret_cast<Int2>(y) & ~sign_bit);  // |y|
  const Int2 swap = n > x;
  const Double2 num = swap ? x : n, den = swap ? n : x;
  const Double2 q = num / den;
  // j = the nearest integer to 8 q, from the bits of 8 q + 1.5 2^52 (exponent of the constant).
  constexpr double round_const = 6755399441055744.0;
  const Double2 shifted = 8.0 * q + round_const;
  const Double2 c = (shifted - round_const) * 0.125;
  const Int2 j = reinterpret_cast<Int2>(shifted) - reinterpret_cast<Int2>(Double2{round_const, round_const});
  const Int2 index = j + (swap & 9);
  const Double2 r = (q - c) / (1.0 + q * c);
  const Double2 r2 = r * r;
  const Double2 P =
      estrin(r2, -3.333333333333333333333333e-01, 2.000000000000000000000000e-01, -1.428571428571428571428571e-01,
             1.111111111111111111111111e-01, -9.090909090909090909090909e-02, 7.692307692307692307692308e-02);
  const Double2 atan_r = r + r * (r2 * P);
  const Double2 hi = {atan_pair_detail::kHi[index[0]], atan_pair_detail::kHi[index[1]]};
  const Double2 lo = {atan_pair_detail::kLo[index[0]], atan_pair_detail::kLo[index[1]]};
  const Double2 res = hi + (lo + (swap ? -atan_r : atan_r));
  return reinterpret_cast<Double2>(reinterpret_cast<Int2>(res) | (reinterpret_cast<Int2>(y) & sign_bit));
}

}  // namespace vgroove::analytic
