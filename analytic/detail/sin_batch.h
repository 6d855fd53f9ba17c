// vgroove analytic: sines and cosines of batches of angles in a known range, by polynomials that
// vectorize (for the BRDF's facet solutions, brdf_3d_batch.cpp).
//
// sin x for x in [-pi/2, pi]: x in (pi/2, pi] is taken as pi - x, formed exactly (Sterbenz)
// plus the low part of pi; then |x| in (pi/4, pi/2] as cos(pi/2 - |x|), formed the same way, so
// that each polynomial runs on |r| <= pi/4: the Taylor series of sin to r^17 and of cos to r^16
// (truncation below 1e-19 there), evaluated in Estrin's order (the latency of three products
// instead of eight). sin and cos of y in [0, pi/2] come from one reduction (sin_cos_quadrant).
//
// Accuracy: within 2 ulp of the correctly rounded value, relative (the polynomials are
// r + r (r^2 P) with |r^2 P| <= 0.11 and (1 - r^2/2) + r^4 Q with r^4 Q <= 0.016; measured in
// tests/analytic/sin_batch_test.cpp against long double). Not bit for bit std::sin. Outside the
// range the result is finite and meaningless; callers guarantee the range.
//
// The templates take a double or a GCC/clang vector of doubles (conditions select lane by lane)
// and are always inlined: instantiated for vectors in a function compiled for AVX2 and in one
// compiled for any x86-64, a shared out-of-line copy would pass its vectors by two conventions.
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
