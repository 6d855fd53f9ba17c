// vgroove sim: the first hit and first reflection of a block of rays of one beam, without branches.
//
// sim::BeamTracer's batch trace computes here, for every ray of a block at once, what trace()
// computes for one ray up to its first reflection: the same products, comparisons and divisions,
// in the same order, so each lane's values are trace()'s bit for bit (tests/sim/beam_tracer_test).
// Only the way is different: every comparison is made, the facet's quantities are picked by
// selects, and the loop has no branch, so the compiler vectorizes it. This file is compiled with
// -fno-trapping-math (sim/CMakeLists.txt), which lets the compiler compute both sides of a select;
// it changes no value, only whether a floating-point exception flag may be raised.
#include "vgroove/common/simd.h"
#include "vgroove/sim/tracer.h"

#include <cmath>
#include <cstdint>

namespace vgroove::sim {

namespace {

// A beam's quantities for the block loops: the position-free parts of trace()'s products, per facet.
struct BeamConsts {
  double x_l, x_r, dy, h_dx;
  double den[2], div[2], ey[2], hex[2], lim[2], len[2];
  double abs_c[2], out_lim[2];  // the first reflection's escape test, per first facet
  std::int64_t leaves[2];
  std::int64_t any;  // 0 sends every ray to trace() (an empty table: max_bounces 0)
};

// One block, every lane computed, no branch. kBoth = false: the beam within the aperture, where
// the sign of cross(p, d) excludes one facet (sim::trace's likely branches; rays where it
// excludes neither go to trace()). kBoth = true: a beam more grazing than a facet, where neither
// is excluded and both are tested in full, as BeamTracer::first_hit_both does (four divisions).
// Bitwise & and |, not && and ||: every comparison is made.
template <bool kBoth>
inline void block_loop(const BeamConsts& c, const double* __restrict x_rim, int n, std::int64_t* __restrict f_out,
                       double* __restrict s_out, std::int64_t* __restrict path_out) {
  for (int j = 0; j < n; ++j) {
    const double x = x_rim[j];
    const double sn = x * c.dy - c.h_dx;
    const std::int64_t inside = (x > c.x_l) & (x < c.x_r);
    const std::int64_t away_l = sn * c.den[0] < 0.0, away_r = sn * c.den[1] < 0.0;
    std::int64_t right, found;
    double s;
    if constexpr (!kBoth) {
      right = away_l;  // the right facet when only the left one is excluded
      const double den = right ? c.den[1] : c.den[0];
      const double ey = right ? c.ey[1] : c.ey[0], hex = right ? c.hex[1] : c.hex[0];
      const double lim = right ? c.lim[1] : c.lim[0];
      found = (away_l ^ away_r) & (den != 0.0) & !((x * ey - hex) * den < 0.0) & !(std::abs(sn) > lim);
      s = sn / (right ? c.div[1] : c.div[0]);
    } else {
      const double tn_l = x * c.ey[0] - c.hex[0], tn_r = x * c.ey[1] - c.hex[1];
      const std::int64_t miss_l = away_l | (c.den[0] == 0.0) | (tn_l * c.den[0] < 0.0) | (std::abs(sn) > c.lim[0]);
      const std::int64_t miss_r = away_r | (c.den[1] == 0.0) | (tn_r * c.den[1] < 0.0) | (std::abs(sn) > c.lim[1]);
      const double s_l = sn / c.div[0], s_r = sn / c.div[1];
      // Both answer: the left one if its s >= 0 and it is nearer by t = tn / den (first_hit_both).
      const std::int64_t left =
          (miss_l ^ 1) & (miss_r | ((s_l >= 0.0) & ((s_r < 0.0) | (tn_l / c.div[0] <= tn_r / c.div[1]))));
      right = left ^ 1;
      found = (miss_l & miss_r) ^ 1;
      s = left ? s_l : s_r;
    }
    // s >= 0 and not on the apex (s == 0) or the rim (s == length): the first reflection happens.
    const std::int64_t ok = c.any & inside & found & (s > 0.0) & (s != (right ? c.len[1] : c.len[0]));
    const std::int64_t out1 = (right ? c.leaves[1] : c.leaves[0]) |
                              (s * (right ? c.abs_c[1] : c.abs_c[0]) > (right ? c.out_lim[1] : c.out_lim[0]));
    s_out[j] = s;
    f_out[j] = right;
    path_out[j] = ok ? (out1 ? 0 : 1) : 2;
  }
}

}  // namespace

// Four rays per instruction in the AVX2 copy (common/simd.h); every lane rounds as trace() does.
VGROOVE_TARGET_CLONES
void BeamTracer::first_hits(const double* __restrict x_rim, int n, BlockHits& __restrict h) const {
  BeamConsts c;
  c.x_l = g_.rim_x(Side::left);
  c.x_r = g_.rim_x(Side::right);
  c.dy = dir_.y();
  c.h_dx = h_dx_;
  // The first reflection per first facet; an empty table (max_bounces 0) sends every ray to trace().
  const bool tables = !table_[0].empty() && !table_[1].empty();
  c.any = tables ? 1 : 0;
  for (int f = 0; f < 2; ++f) {
    c.den[f] = den_[f];
    // Divisors never zero (a zero denominator is a miss, masked), so every lane may divide.
    c.div[f] = den_[f] != 0.0 ? den_[f] : 1.0;
    c.ey[f] = g_.facet[f].edge.y();
    c.hex[f] = h_ex_[f];
    c.lim[f] = limit_[f];
    c.len[f] = g_.facet[f].length;
    const Reflection e = tables ? table_[f][0] : Reflection{};
    c.abs_c[f] = e.abs_c;
    c.out_lim[f] = e.limit;
    c.leaves[f] = e.leaves;
  }
  // Denominators of opposite signs: the beam is within the aperture, and for every ray off the
  // line through the apex the sign of cross(p, d) excludes one facet. Otherwise it excludes
  // neither (or both) for every ray of the opening: both are tested.
  if (den_[0] * den_[1] < 0.0)
    block_loop<false>(c, x_rim, n, h.f, h.s, h.path);
  else
    block_loop<true>(c, x_rim, n, h.f, h.s, h.path);
}

}  // namespace vgroove::sim
