// vgroove analytic: sines and cosines of batches of angles in a known range, by polynomials that
// vectorize (for the BRDF's facet solutions, brdf_3d_batch.cpp): sin x for x in [-pi/2, pi] and
// sin_cos_quadrant for y in [0, pi/2], reduced exactly to |r| <= pi/4, Taylor series in Estrin's
// order. Accuracy: within 2 ulp of the correctly rounded value, relative (not bit for bit
// std::sin); outside the range finite and meaningless. Templates over a double or a vector of
// doubles, always inlined (the callers are compiled twice).
// Tests: tests/analytic/sin_batch_test.cpp (SinBatch.WithinTwoUlpOverItsRange).
// Derivation: docs/derivations/numerics.md.
#pragma once

#include "vgroove/common/polynomial.h"

#if defined(__GNUC__) && !defined(__clang__)
#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wpsabi"  // common/simd.h
#endif

namespace vgroove::analytic {

// y[m] = sin(x[m]) for m < n, x[m] in [-pi/2, pi]; x and y may be the same array.
void sin_batch(const double* x, double* y, int n);

// The argument whose sine is cos(y), y in [0, pi/2]: pi/2 - y with pi/2's low part added.
template <typename T>
[[gnu::always_inline]] inline T cos_arg(T y) {
  return (1.5707963267948966 - y) + 6.123233995736766036e-17;  // pi/2 = 1.5707963267948966 + 6.1e-17
}

// sin r for |r| <= pi/4: r + r (r^2 P(r^2)), P the Taylor coefficients -1/3!, ..., 1/17!.
template <typename T>
[[gnu::always_inline]] inline T sin_pi4(T r) {
  const T y = r * r;
  const T P = estrin(y, -1.666666666666666666666667e-01, 8.333333333333333333333333e-03,
                     -1.984126984126984126984127e-04, 2.755731922398589065255732e-06, -2.505210838544171877505211e-08,
                     1.605904383682161459939238e-10, -7.647163731819816475901132e-13, 2.811457254345520763198946e-15);
  return r + r * (y * P);
}

// cos r for |r| <= pi/4: (1 - r^2/2) + r^4 Q(r^2), Q the Taylor coefficients 1/4!, ..., 1/16!.
template <typename T>
[[gnu::always_inline]] inline T cos_pi4(T r) {
  const T y = r * r;
  const T Q = estrin(y, 4.166666666666666666666667e-02, -1.388888888888888888888889e-03, 2.480158730158730158730159e-05,
                     -2.755731922398589065255732e-07, 2.087675698786809897921009e-09, -1.147074559772972471385170e-11,
                     4.779477332387385297438207e-14);
  return (1.0 - 0.5 * y) + (y * y) * Q;
}

// sin x for x in [-pi/2, pi].
template <typename T>
[[gnu::always_inline]] inline T sin_full(T x) {
  const T u = x > 1.5707963267948966 ? (3.141592653589793 - x) + 1.2246467991473532e-16 : x;  // pi - x
  const T v = u < 0.0 ? -u : u;
  const auto big = v > 0.7853981633974483;
  const T r = big ? cos_arg(v) : v;
  const T s = big ? cos_pi4(r) : sin_pi4(r);
  return u < 0.0 ? -s : s;
}

// sin x and cos x for x in [0, pi/2], from one reduction.
template <typename T>
[[gnu::always_inline]] inline void sin_cos_quadrant(T x, T& s, T& c) {
  const auto big = x > 0.7853981633974483;
  const T r = big ? cos_arg(x) : x;
  const T sr = sin_pi4(r), cr = cos_pi4(r);
  s = big ? cr : sr;
  c = big ? sr : cr;
}

}  // namespace vgroove::analytic

#if defined(__GNUC__) && !defined(__clang__)
#pragma GCC diagnostic pop
#endif
