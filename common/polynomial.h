// vgroove common: a polynomial c0 + c1 x + ... + cn x^n from its coefficients, in Horner's or
// Estrin's order, for a double or a vector of doubles (common/simd.h; the coefficients are doubles,
// broadcast to every lane).
//
// horner(x, c0, ..., cn) = c0 + x (c1 + x (c2 + ... + x cn)): n dependent products.
// estrin(x, c0, ..., cn): the coefficients paired, c_2i + c_2i+1 x, then the pairs paired with x^2,
// those with x^4 and so on (x^2, x^4, ... each the square of the one before; an odd one out at a
// level passes unchanged to the next): the latency of about log2(n) products instead of n. E.g.
// estrin(x, c0, ..., c6) = ((c0 + c1 x) + (c2 + c3 x) x^2) + ((c4 + c5 x) + c6 x^2) x^4. Either
// order fixes every rounding, so a polynomial written with them rounds the same for double and
// for every lane of a vector.
#pragma once

#include <cstddef>

#if defined(__GNUC__) && !defined(__clang__)
#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wpsabi"  // common/simd.h
#endif

namespace vgroove {

template <typename T>
[[gnu::always_inline]] inline T horner(T, double c0) {
  return T{} + c0;
}
template <typename T, typename... C>
[[gnu::always_inline]] inline T horner(T x, double c0, double c1, C... c) {
  if constexpr (sizeof...(C) == 0) {
    return c0 + x * c1;
  } else {
    return c0 + x * horner(x, c1, c...);
  }
}

namespace polynomial_detail {

// x^M, M a power of 2, as the square of x^(M/2).
template <std::size_t M, typename T>
[[gnu::always_inline]] inline T power(T x) {
  if constexpr (M == 1) {
    return x;
  } else {
    const T h = power<M / 2>(x);
    return h * h;
  }
}

// The largest power of 2 below N (N >= 2).
constexpr std::size_t split(std::size_t N) {
  std::size_t m = 1;
  while (2 * m < N) m *= 2;
  return m;
}

// c[L] + c[L+1] x + ... + c[L+N-1] x^(N-1) in Estrin's order: the lower m coefficients plus x^m
// times the others, m the largest power of 2 below N, which pairs the terms level by level.
template <std::size_t L, std::size_t N, typename T, std::size_t K>
[[gnu::always_inline]] inline auto part(T x, const double (&c)[K]) {
  if constexpr (N == 1) {
    return c[L];
  } else if constexpr (N == 2) {
    return c[L] + c[L + 1] * x;
  } else {
    constexpr std::size_t m = split(N);
    return part<L, m>(x, c) + part<L + m, N - m>(x, c) * power<m>(x);
  }
}

}  // namespace polynomial_detail

template <typename T, typename... C>
[[gnu::always_inline]] inline T estrin(T x, double c0, double c1, C... c) {
  const double cs[] = {c0, c1, static_cast<double>(c)...};
  return polynomial_detail::part<0, 2 + sizeof...(C)>(x, cs);
}

}  // namespace vgroove

#if defined(__GNUC__) && !defined(__clang__)
#pragma GCC diagnostic pop
#endif
