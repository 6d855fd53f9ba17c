// vgroove common: four doubles at a time (GCC and clang vector extensions) for the kernels that
// take four rays, angles or quadrature nodes per instruction. V4 arithmetic is lane by lane and
// rounds as double does; comparisons give masks, select(mask, a, b) picks lanes.
// VGROOVE_TARGET_CLONES compiles a function for AVX2 and for any x86-64 and picks one at start-up;
// the libraries build with -ffp-contract=off, so both copies round alike and as the scalar code.
// Helpers are always inlined. Held by the kernels' bit-for-bit tests:
// tests/sim/symmetric_block_test.cpp (SymmetricBlock.EveryRayIsTracesBitForBit),
// tests/analytic/brdf_3d_test.cpp (Brdf3d.BatchedPassEqualsPerSolutionPass).
// Derivation: docs/derivations/numerics.md.
#pragma once

#include <cstdint>
#include <cstring>

#if defined(__x86_64__) && defined(__GNUC__) && !defined(__clang__)
#define VGROOVE_TARGET_CLONES [[gnu::target_clones("avx2", "default")]]
#else
#define VGROOVE_TARGET_CLONES
#endif

#if defined(__GNUC__) && !defined(__clang__)
#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wpsabi"
#endif

namespace vgroove::simd {

typedef double V4 __attribute__((vector_size(32)));
typedef std::int64_t I4 __attribute__((vector_size(32)));
// Two lanes (SSE2 in any x86-64 copy).
typedef double V2 __attribute__((vector_size(16)));
typedef std::int64_t I2 __attribute__((vector_size(16)));

[[gnu::always_inline]] inline V4 splat(double x) { return V4{x, x, x, x}; }
// Four doubles from p or to p, with no alignment asked for.
[[gnu::always_inline]] inline V4 load(const double* p) {
  V4 v;
  std::memcpy(&v, p, sizeof v);
  return v;
}
[[gnu::always_inline]] inline void store(double* p, V4 v) { std::memcpy(p, &v, sizeof v); }
[[gnu::always_inline]] inline I4 load(const std::int64_t* p) {
  I4 v;
  std::memcpy(&v, p, sizeof v);
  return v;
}
// |a| lane by lane (the sign bit cleared).
[[gnu::always_inline]] inline V4 abs(V4 a) {
  constexpr std::int64_t m = ~(std::int64_t{1} << 63);
  return reinterpret_cast<V4>(reinterpret_cast<I4>(a) & I4{m, m, m, m});
}
// a where the mask is set, b elsewhere, lane by lane (both sides are computed).
template <typename Mask, typename V>
[[gnu::always_inline]] inline V select(Mask m, V a, V b) {
  return m ? a : b;
}
// Whether any lane of a mask is set.
template <typename Mask>
[[gnu::always_inline]] inline bool any(Mask m) {
  return (m[0] | m[1] | m[2] | m[3]) != 0;
}

}  // namespace vgroove::simd

#if defined(__GNUC__) && !defined(__clang__)
#pragma GCC diagnostic pop
#endif
