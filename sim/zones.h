// vgroove sim: the exact traced fractions of a parallel beam, by breakpoint search. A ray's outcome
// (termination, facet hit first, bounce count k) is piecewise constant in where it crosses the rim
// line; find_zones traces a stratified grid plus the interval's ends and bisects between
// neighbours of different outcome down to adjacent doubles, so every breakpoint is located to the
// ulp and each outcome's fraction is the measure of its zones. Only the tracer decides outcomes.
// A zone can be missed only between grid rays of equal outcome; in a V-groove none exists (the
// convexity lemma: x enters every test of the tracer affinely, so each outcome's set is an
// interval), so such cells are certified; other cells are halved up to kSplits times and the rest
// is counted in uncertified_cells, bounded by missed_bound(). Nothing is dropped silently.
// Tests: tests/sim/zones_test.cpp (Zones.BreakpointsAreFoundToTheUlp,
// Zones.AHiddenZoneIsReportedAsPossiblyMissed, Zones.UncertifiedCellsAreHalvedBeforeTheyAreCounted,
// ZonesVGroove.EveryRayHasItsZonesOutcome, Zones.BreakpointsNearZeroStopAtTheIntervalsUlp).
// Derivation: docs/derivations/zones.md.
#pragma once

#include "vgroove/sim/beam.h"
#include "vgroove/sim/tracer.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <vector>

namespace vgroove::sim {

// Whether two rays have the same outcome: termination, and for rays that entered the groove the
// facet hit first and the bounce count.
inline bool same_outcome(const TraceResult& a, const TraceResult& b) {
  if (a.how != b.how) return false;
  if (a.how == Termination::blocked) return true;
  return a.first == b.first && a.bounces == b.bounces;
}

// Whether two grid rays of outcome r certify the cell between them (the convexity lemma).
inline bool lemma_covers(const TraceResult& r) { return r.how != Termination::vertex_hit; }

struct Zone {
  double lo = 0.0, hi = 0.0;  // [lo, hi) on the rim line
  TraceResult ray;            // the outcome of its rays (one traced ray's result)
  double width() const { return hi - lo; }
};

struct ZoneSearch {
  std::vector<Zone> zones;  // in order, contiguous, from the interval's lo to its hi
  long grid = 0;            // rays of the stratified grid (M); the two ends are traced besides
  long traced = 0;          // every ray traced: grid, ends, bisection
  std::int64_t bounces = 0;
  long uncertified_cells = 0;      // cells with equal ends that no certificate covers (after kSplits halvings)
  double uncertified_width = 0.0;  // their total width, on the rim line
  double spacing = 0.0;            // of the grid, on the rim line
  // What the zones may miss, on the rim line: the uncertified cells, each narrower than the
  // spacing, may hide zones.
  double missed_bound() const { return uncertified_width; }
  // The narrowest zone found, on the rim line (0 when there is none); vertex hits (points, or a
  // few ulps where a rounded position lands on a facet's end) left out.
  double narrowest() const {
    double w = 0.0;
    for (const Zone& z : zones)
      if (z.ray.how != Termination::vertex_hit) w = (w == 0.0 || z.width() < w) ? z.width() : w;
    return w;
  }
};

// How often a grid cell whose equal ends certify nothing is halved before it is counted.
inline constexpr int kSplits = 8;

namespace detail {

// The breakpoints between a (outcome ra) and b (outcome rb != ra), in order: bisection on x down
// to adjacent doubles, or to `resolution` (the ulp of the interval's ends: near x = 0 adjacent
// doubles are far finer than any position the beam can be placed at, and would take a thousand
// halvings); a third outcome at a midpoint splits the search in two, left part first.
template <class Trace, class Boundary>
void refine(double a, TraceResult ra, double b, TraceResult rb, double resolution, Trace& trace, Boundary& boundary) {
  for (;;) {
    const double mid = a + 0.5 * (b - a);
    if (!(mid > a && mid < b) || b - a <= resolution) {
      boundary(b, rb);  // adjacent doubles: the outcome changes within (a, b]
      return;
    }
    const TraceResult rm = trace(mid);
    if (same_outcome(rm, ra)) {
      a = mid;
    } else if (same_outcome(rm, rb)) {
      b = mid;
    } else {
      refine(a, ra, mid, rm, resolution, trace, boundary);
      a = mid;
      ra = rm;
    }
  }
}

}  // namespace detail

// The zones of the interval iv: trace_block(x, n, out) traces n rays at the positions x (the
// grid, a block at a time), trace(x) one ray, certified(r) says whether two grid rays of outcome
// r certify the cell between them, observe(x, r) sees every traced ray. M >= 1.
template <class TraceBlock, class Trace, class Certified, class Observe>
ZoneSearch find_zones(const Interval& iv, long M, TraceBlock&& trace_block, Trace&& trace, Certified&& certified,
                      Observe&& observe) {
  ZoneSearch zs;
  zs.grid = M;
  zs.spacing = iv.width() / static_cast<double>(M);
  // Breakpoints to the ulp of the interval's ends (adjacent doubles there).
  const double resolution = std::ldexp(std::max(std::abs(iv.lo), std::abs(iv.hi)), -52);
  auto traced = [&](double x) {
    const TraceResult r = trace(x);
    ++zs.traced;
    zs.bounces += r.bounces;
    observe(x, r);
    return r;
  };
  auto boundary = [&](double x, const TraceResult& r) {
    if (x <= zs.zones.back().lo) {  // two breakpoints at one position: the zone between is empty
      zs.zones.back().ray = r;
      return;
    }
    zs.zones.back().hi = x;
    zs.zones.push_back(Zone{x, iv.hi, r});
  };
  // The cell from (x0, r0) to (x1, r1). Equal ends without a certificate (vertex hits) are
  // split at their midpoint, down to kSplits levels, so that a ray inside may certify or refine
  // them; what is left then is counted.
  auto cell = [&](auto& self, double x0, const TraceResult& r0, double x1, const TraceResult& r1, int depth) -> void {
    if (!same_outcome(r0, r1)) {
      detail::refine(x0, r0, x1, r1, resolution, traced, boundary);
      return;
    }
    if (certified(r0)) return;
    const double mid = x0 + 0.5 * (x1 - x0);
    if (depth == kSplits || !(mid > x0 && mid < x1) || x1 - x0 <= resolution) {
      ++zs.uncertified_cells;
      zs.uncertified_width += x1 - x0;
      return;
    }
    const TraceResult rm = traced(mid);
    self(self, x0, r0, mid, rm, depth + 1);
    self(self, mid, rm, x1, r1, depth + 1);
  };
  // The interval's lo and hi are a rim or the apex line (measure zero): the ends traced are the
  // nearest doubles inside.
  const double end_lo = std::nextafter(iv.lo, iv.hi), end_hi = std::nextafter(iv.hi, iv.lo);
  double x_prev = end_lo;
  TraceResult r_prev = traced(end_lo);
  zs.zones.push_back(Zone{iv.lo, iv.hi, r_prev});
  double x[BeamTracer::kBlock];
  TraceResult r[BeamTracer::kBlock];
  Rng unused(0, 0, 0);
  for (long j0 = 0; j0 < M; j0 += BeamTracer::kBlock) {
    const int m = static_cast<int>(std::min<long>(BeamTracer::kBlock, M - j0));
    sample_positions(Sampling::stratified, iv, j0, m, M, unused, x);
    trace_block(x, m, r);
    for (int j = 0; j < m; ++j) {
      ++zs.traced;
      zs.bounces += r[j].bounces;
      observe(x[j], r[j]);
      // The grid's positions increase; an interval narrower than its own ulps may repeat one.
      if (x[j] > x_prev && x[j] < end_hi) {
        cell(cell, x_prev, r_prev, x[j], r[j], 0);
        x_prev = x[j];
        r_prev = r[j];
      }
    }
  }
  const TraceResult r_hi = traced(end_hi);
  if (end_hi > x_prev) cell(cell, x_prev, r_prev, end_hi, r_hi, 0);
  zs.zones.back().hi = iv.hi;
  return zs;
}

// The zones of a beam in a V-groove, traced by its BeamTracer (the grid with the batch trace),
// cells certified by the convexity lemma.
template <class Observe>
ZoneSearch find_zones(const BeamTracer& beam, const Interval& iv, long M, Observe&& observe) {
  return find_zones(
      iv, M, [&](const double* x, int n, TraceResult* out) { beam.trace(x, n, out); },
      [&](double x) { return beam.trace(x); }, lemma_covers, observe);
}

}  // namespace vgroove::sim
