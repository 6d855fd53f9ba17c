// vgroove sim: the reflections of a block of rays, each in its own symmetric groove and with its
// own direction, without branches (the procedural surfaces' batch trace). A groove is three
// numbers (SymmetricGrooveData, 24 bytes), from which everything sim::trace reads is formed by the
// same operations (symmetric_groove_from). first_reflections and next_reflections compute, four
// lanes per vector (common/simd.h), what sim::trace computes, the same operations in the same
// order with selects for branches, so each lane's values are trace()'s bit for bit (AVX2 without
// FMA, -fno-trapping-math). Rays the block does not settle go on in sim::trace.
// Tests: tests/sim/symmetric_block_test.cpp (SymmetricBlock.EveryRayIsTracesBitForBit,
// SymmetricBlock.GrooveDataRebuildsTheGroove, SymmetricBlock.TalliesEqualThePathBefore,
// SymmetricBlock.ChunksAddedIntoOneTallyEqualTheMergedChunks).
// Derivation: docs/derivations/microsurface.md.
#pragma once

#include "vgroove/sim/groove.h"
#include "vgroove/sim/tracer.h"

#include <cstdint>

namespace vgroove::sim {

// A symmetric groove of unit facets: its left and right edges' x (-sin(theta_v/2) and the right
// edge's own, +sin(theta_v/2)) and the rim height cos(theta_v/2), as make_symmetric_groove forms
// them.
struct SymmetricGrooveData {
  double left_x = 0.0, right_x = 0.0, rim_height = 1.0;
};
SymmetricGrooveData symmetric_groove_data(const Groove& g);
// The groove itself, bit for bit make_symmetric_groove's (but theta_v, which trace() does not read).
Groove symmetric_groove_from(const SymmetricGrooveData& d);

inline constexpr int kSymmetricBlock = 256;

// A block of rays: rim-line crossing x, direction (dx, dy), groove.
struct SymmetricBlock {
  double x[kSymmetricBlock], dx[kSymmetricBlock], dy[kSymmetricBlock];
  double left_x[kSymmetricBlock], right_x[kSymmetricBlock], rim_height[kSymmetricBlock];
};

// What the block knows of its rays: f the facet hit first, k the reflections so far and the
// path: 0, the ray left along (d1x, d1y) after k reflections; 1, it is at s on facet `on`,
// travelling along (d1x, d1y) (trace()'s state after k bounces); 2, anything else, for sim::trace
// to take from the start; 3, it met a vertex (the apex or a rim) after k reflections; 4, it
// reached max_bounces. 64-bit lanes for the vectorizer.
struct SymmetricHits {
  double s[kSymmetricBlock], d1x[kSymmetricBlock], d1y[kSymmetricBlock];
  std::int64_t f[kSymmetricBlock], on[kSymmetricBlock], k[kSymmetricBlock], path[kSymmetricBlock];
};

// The first reflections of lanes [0, n), n <= kSymmetricBlock (max_bounces >= 1): paths 0, 1, 2.
void first_reflections(const SymmetricBlock& in, int n, SymmetricHits& out);
// One more reflection of every lane on path 1 (trace()'s bounce(), every comparison made); the
// number of lanes still on path 1 after it.
int next_reflections(const SymmetricBlock& in, int n, int max_bounces, SymmetricHits& h);
// first_reflections, then rounds of next_reflections while at least kBlockMinLanes lanes are on
// path 1, at most `rounds` times: on the whole block while at least a quarter of its lanes is on
// path 1 (a round costs every lane it is given), then on those lanes gathered, gathered again
// whenever fewer than a quarter of them remain. Every lane's values are next_reflections' on the
// whole block, bit for bit.
void block_reflections(const SymmetricBlock& in, int n, int max_bounces, int rounds, SymmetricHits& h);
// Rounds of next_reflections: most rays of rough surfaces settle within a few reflections; the
// rest (narrow grooves) go on one by one once fewer than kBlockMinLanes are left.
inline constexpr int kBlockRounds = 32;
inline constexpr int kBlockMinLanes = 8;

// The whole trace of lane j, bit for bit sim::trace(symmetric_groove_from(...), the lane's ray, opt).
inline TraceResult finish_lane(const SymmetricBlock& in, const SymmetricHits& h, int j, const TraceOptions& opt) {
  const SymmetricGrooveData gd{in.left_x[j], in.right_x[j], in.rim_height[j]};
  TraceResult r;
  const std::int64_t path = h.path[j];
  const int k = static_cast<int>(h.k[j]);
  r.first = static_cast<Side>(h.f[j]);
  if (path == 0) [[likely]] {
    detail::finish(r, detail::Step::escaped, k, Vec2(h.d1x[j], h.d1y[j]));
    return r;
  }
  if (path == 3 || path == 4) {
    detail::finish(r, path == 3 ? detail::Step::vertex_hit : detail::Step::bounce_limit, k, Vec2(h.d1x[j], h.d1y[j]));
    return r;
  }
  const Groove g = symmetric_groove_from(gd);
  if (path == 1) {
    Vec2 d(h.d1x[j], h.d1y[j]);
    double s = h.s[j];
    int bounces = k;
    NoBounceObserver obs;
    const detail::Step st =
        detail::reflect_until_done(g, static_cast<Side>(h.on[j]), d, s, bounces, opt.max_bounces, obs);
    detail::finish(r, st, bounces, d);
    return r;
  }
  r = TraceResult{};
  return trace(g, Ray2{Vec2(in.x[j], in.rim_height[j]), Vec2(in.dx[j], in.dy[j])}, opt);
}

}  // namespace vgroove::sim
