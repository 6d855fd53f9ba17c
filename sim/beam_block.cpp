// vgroove sim: the first hit and first reflection of a block of rays of one beam, without branches.
//
// sim::BeamTracer's batch trace computes here, for every ray of a block at once, what trace()
// computes for one ray up to its first reflection: the same products, comparisons and division,
// in the same order, so each lane's values are trace()'s bit for bit (tests/sim/beam_tracer_test).
// Only the way is different: every comparison is made, the facet's quantities are picked by
// selects, and the loop has no branch, so the compiler vectorizes it. This file is compiled with
// -fno-trapping-math (sim/CMakeLists.txt), which lets the compiler compute both sides of a select;
// it changes no value, only whether a floating-point exception flag may be raised.
#include "sim/tracer.h"

#include <cmath>
#include <cstdint>

namespace vgroove::sim {

// The path of trace(): the same products, comparisons and division, every lane computed and the
// facet's quantities picked by selects, so that the loop has no branch.
#if defined(__x86_64__) && defined(__GNUC__) && !defined(__clang__)
// One copy of the loop for AVX2 (four rays per instruction) and one for any x86-64, picked when
// the program starts. AVX2 without FMA: no product is fused, so every lane rounds as trace() does.
[[gnu::target_clones("avx2", "default")]]
#endif
void BeamTracer::first_hits(const double* __restrict x_rim, int n, BlockHits& __restrict h) const {
  const double x_l = g_.rim_x(Side::left), x_r = g_.rim_x(Side::right);
  const double dy = dir_.y(), h_dx = h_dx_;
  const double den0 = den_[0], den1 = den_[1];
  // Divisors never zero (a zero denominator is a miss, masked below), so the division is safe in
  // every lane and the compiler need not guard it.
  const double div0 = den0 != 0.0 ? den0 : 1.0, div1 = den1 != 0.0 ? den1 : 1.0;
  const double ey0 = g_.facet[0].edge.y(), ey1 = g_.facet[1].edge.y();
  const double hex0 = h_ex_[0], hex1 = h_ex_[1];
  const double lim0 = limit_[0], lim1 = limit_[1];
  const double len0 = g_.facet[0].length, len1 = g_.facet[1].length;
  // The first reflection per first facet; an empty table (max_bounces 0) sends every ray to trace().
  const bool tables = !table_[0].empty() && !table_[1].empty();
  const Reflection none{};
  const Reflection& r0 = tables ? table_[0][0] : none;
  const Reflection& r1 = tables ? table_[1][0] : none;
  const double abs_c0 = r0.abs_c, abs_c1 = r1.abs_c, out_lim0 = r0.limit, out_lim1 = r1.limit;
  const std::int64_t leaves0 = r0.leaves, leaves1 = r1.leaves;
  const std::int64_t any = tables ? 1 : 0;  // & with this sends every ray to trace() when 0
  for (int j = 0; j < n; ++j) {
    const double x = x_rim[j];
    const double sn = x * dy - h_dx;
    // Bitwise & and |, not && and ||: every comparison is made, and the loop has no branch.
    const std::int64_t inside = (x > x_l) & (x < x_r);
    const std::int64_t away_l = sn * den0 < 0.0, away_r = sn * den1 < 0.0;
    const std::int64_t right = away_l;  // the right facet when only the left one is excluded
    const std::int64_t one = away_l ^ away_r;
    const double den = right ? den1 : den0;
    const double ey = right ? ey1 : ey0, hex = right ? hex1 : hex0, lim = right ? lim1 : lim0;
    const double len = right ? len1 : len0;
    const std::int64_t hit = (den != 0.0) & !((x * ey - hex) * den < 0.0) & !(std::abs(sn) > lim);
    const double s = sn / (right ? div1 : div0);
    // s >= 0 and not on the apex (s == 0) or the rim (s == length): the first reflection happens.
    const std::int64_t ok = any & inside & one & hit & (s > 0.0) & (s != len);
    const std::int64_t leaves = right ? leaves1 : leaves0;
    const std::int64_t out1 = leaves | (s * (right ? abs_c1 : abs_c0) > (right ? out_lim1 : out_lim0));
    h.s[j] = s;
    h.f[j] = right;
    h.path[j] = ok ? (out1 ? 0 : 1) : 2;
  }
}

}  // namespace vgroove::sim
