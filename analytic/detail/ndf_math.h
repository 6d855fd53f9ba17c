// vgroove analytic: the elementary functions the NDF formulas (ndf_ggx.h, ndf_beckmann.h, ndf_phong.h,
// ndf_student_t.h) are written with, for a double (the C library's functions) and for four lanes
// (simd::V4: the polynomials of exp_log_batch.h and the correctly rounded square root), so that one
// formula serves the scalar passes and the vector kernels (brdf_3d_batch.cpp, lobe_3d_nodes.cpp).
//
// The vector forms hold on the ranges the kernels use, said per function: exp_nonpositive and pow
// are 0 where the exponent is below -708 (the polynomial's range starts there; e^-708 ~ 3e-308);
// log needs a positive normal number; expm1 an argument in [-708, 709]. Accuracy: exp_log_batch.h
// (within 2 ulp, a power adding its exponent's rounding) against the library's correctly rounded
// or nearly so values: the vector kernels agree with the scalar ones within rounding, not bit for bit.
#pragma once

#include "vgroove/analytic/detail/exp_log_batch.h"
#include "vgroove/common/simd.h"

#include <cmath>
#include <type_traits>

#if defined(__GNUC__) && !defined(__clang__)
#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wpsabi"  // common/simd.h
#endif

namespace vgroove::analytic::ndf_math {

using simd::V4;

inline double sqrt(double x) { return std::sqrt(x); }
// Lane by lane, the correctly rounded square root (without errno where the file says
// -fno-math-errno; otherwise a negative lane calls the library, with the same NaN).
[[gnu::always_inline]] inline V4 sqrt(V4 x) {
  return V4{__builtin_sqrt(x[0]), __builtin_sqrt(x[1]), __builtin_sqrt(x[2]), __builtin_sqrt(x[3])};
}

// e^z for z <= 0.
inline double exp_nonpositive(double z) { return std::exp(z); }
[[gnu::always_inline]] inline V4 exp_nonpositive(V4 z) {
  const V4 zero = simd::splat(0.0);
  const V4 e = batch::exp_batch(z >= -708.0 ? z : zero);
  return z >= -708.0 ? e : zero;
}

inline double expm1(double z) { return std::expm1(z); }
[[gnu::always_inline]] inline V4 expm1(V4 z) { return batch::expm1_batch(z); }

inline double log(double x) { return std::log(x); }
[[gnu::always_inline]] inline V4 log(V4 x) { return batch::log_batch(x); }

// c^p for c > 0 (a normal number in the vector form, where p log c is clamped to 709 above).
inline double pow(double c, double p) { return std::pow(c, p); }
[[gnu::always_inline]] inline V4 pow(V4 c, double p) {
  if (p == 0.0) return simd::splat(1.0);
  const V4 z = p * batch::log_batch(c);
  const V4 e = batch::exp_batch(z >= -708.0 ? (z <= 709.0 ? z : simd::splat(709.0)) : simd::splat(0.0));
  return z >= -708.0 ? e : simd::splat(0.0);
}

// cos and sin of atan(t), t >= 0, without overflow: for t <= 1, c = 1 / sqrt(1 + t^2), s = t c;
// beyond, with m = 1 / t, s = 1 / sqrt(1 + m^2), c = m s. The vector form computes both sides and
// selects, with one square root on the selected m: the same operations in every lane.
template <typename T>
[[gnu::always_inline]] inline void cos_sin_of_atan(T t, T& c, T& s) {
  if constexpr (std::is_same_v<T, double>) {
    if (t <= 1.0) {
      c = 1.0 / std::sqrt(1.0 + t * t);
      s = t * c;
    } else {
      const double r = 1.0 / t;
      s = 1.0 / std::sqrt(1.0 + r * r);
      c = r * s;
    }
  } else {
    const auto low = t <= 1.0;
    const T m = low ? t : 1.0 / t;
    const T q = 1.0 / sqrt(1.0 + m * m), a = m * q;
    c = low ? q : a;
    s = low ? a : q;
  }
}

// cos and sin of theta from 1 - cos theta = omc in [0, 1]: sin = sqrt(omc (2 - omc)), which keeps
// small angles exact.
template <typename T>
[[gnu::always_inline]] inline void cos_sin_of_one_minus_cos(T omc, T& c, T& s) {
  c = 1.0 - omc;
  s = sqrt(omc * (2.0 - omc));
}

}  // namespace vgroove::analytic::ndf_math

#if defined(__GNUC__) && !defined(__clang__)
#pragma GCC diagnostic pop
#endif
