// vgroove sim: where the rays of a parallel beam cross the rim line.
//
// A beam from incident angle theta_i is parallel; crossing the rim line, its rays are spread
// along x. Uniform spacing along the rim line is uniform spacing across the beam (the map from
// perpendicular offset to x is affine), so a placement along x has the beam's own measure.
#pragma once

#include "vgroove/sim/groove.h"
#include "vgroove/sim/rng.h"
#include "vgroove/sim/tracer.h"

#include <algorithm>
#include <atomic>

namespace vgroove::sim {

enum class Sampling : unsigned char {
  stratified,   // midpoints of N equal strata
  random,       // independent uniform positions from a seeded stream
  breakpoints,  // the zones of equal outcome, found by a search from a stratified grid (sim/zones.h)
};
const char* sampling_name(Sampling s);

struct Interval {
  double lo, hi;
  double width() const { return hi - lo; }
};

// The groove's opening on the rim line.
Interval opening(const Groove& g);

// Rays aimed at one facet, as if the other were absent: between the rim line crossings of the
// lines through the apex and through the facet's rim (the facet's projected width, the paper's
// f_a). The part of it outside the opening is shadowed by the other facet's rim.
Interval aimed_at(const Groove& g, double theta_i, Side side);

// Position of ray j of n in the interval (stratified or random placement; breakpoints place
// their grid as stratified).
inline double sample_position(Sampling sampling, const Interval& iv, long j, long n, Rng& rng) {
  const double u =
      sampling != Sampling::random ? (static_cast<double>(j) + 0.5) / static_cast<double>(n) : rng.uniform();
  return iv.lo + u * (iv.hi - iv.lo);
}

// Positions of rays j0, ..., j0 + count - 1 of n into out: out[i] == sample_position(sampling, iv,
// j0 + i, n, rng) for each i in turn (random placement draws the stream's next count numbers).
// Stratified positions of a block are computed together (vectorized), bit for bit the same.
void sample_positions(Sampling sampling, const Interval& iv, long j0, int count, long n, Rng& rng, double* out);

// Traces the n rays of a beam placed over iv (sample_position's rays 0..n-1, in order) with the
// batch trace, a block at a time, and hands each result to fn(j, result). Before each block of
// `block` rays (1..kBlock; the results do not depend on it) `cancel` is read, when given: once it
// is set the beam stops there, and trace_beam returns false (true when all n rays were traced).
template <class Fn>
bool trace_beam(const BeamTracer& beam, Sampling sampling, const Interval& iv, long n, Rng& rng, Fn&& fn,
                const std::atomic<bool>* cancel = nullptr, int block = BeamTracer::kBlock) {
  double x[BeamTracer::kBlock];
  TraceResult traced[BeamTracer::kBlock];
  block = std::clamp(block, 1, BeamTracer::kBlock);
  for (long j0 = 0; j0 < n; j0 += block) {
    if (cancel && cancel->load(std::memory_order_relaxed)) return false;
    const int m = static_cast<int>(std::min<long>(block, n - j0));
    sample_positions(sampling, iv, j0, m, n, rng, x);
    beam.trace(x, m, traced);
    for (int j = 0; j < m; ++j) fn(j0 + j, traced[j]);
  }
  return true;
}

// The direction the beam's rays travel in: -i.
inline Vec2 beam_direction(double theta_i) { return -direction_at(theta_i); }

// The ray of the beam travelling along dir that crosses the rim line at x.
inline Ray2 beam_ray(const Groove& g, const Vec2& dir, double x) { return Ray2{Vec2(x, g.rim_height), dir}; }

}  // namespace vgroove::sim
