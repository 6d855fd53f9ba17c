// vgroove sim: exact 2D ray tracing over a periodic polyline height profile (sim/polyline.h),
// with the rules of sim/tracer.h: explicit ray-segment intersections, mirror reflections, no
// epsilon offsets (the segment just hit is excluded), and every ray in one Termination bucket
// (escaped, vertex_hit, bounce_limit). The first hit is watertight: each vertex's side of the ray
// is computed once and shared by its two segments, so no ray slips through a common vertex; blocks
// of the pyramid are skipped only when conservatively below the ray. A ray going up that passes a
// whole period without a hit never hits; one going down always hits within a period.
// Tests: tests/sim/polyline_tracer_test.cpp (PolylineTracer.EveryStepIsTheBruteForceHit,
// PolylineTracer.RaysExactlyThroughVerticesAreVertexHits, PolylineTracer.ReflectionLawAndEnergyAtEveryBounce,
// PolylineTracer.GrazingLightNearFlatAndVeryRoughProfilesLoseNoRay,
// PolylineTracer.VGrooveSurfaceGivesTheGrooveTracersRays).
// Derivation: docs/derivations/profiles.md.
#pragma once

#include "vgroove/sim/polyline.h"
#include "vgroove/sim/tracer.h"

#include <vector>

namespace vgroove::sim {

struct PolylineHit {
  enum class Kind : unsigned char { segment, vertex, escaped };
  Kind kind = Kind::escaped;
  int segment = -1;  // kind == segment: the segment met, in the base period
  double s = 0.0;    // its parameter from vertex `segment` (0) to vertex `segment + 1` (1), in (0, 1)
};

// The first hit of the ray entering from the top line y = y_max at x in [x_0, x_0 + period),
// travelling along dir (unit, dir.y < 0).
PolylineHit first_hit_from_top(const Polyline& p, double x, const Vec2& dir);

// The first hit of the ray leaving the point at parameter s of segment j along dir (unit), the
// segment itself excluded.
PolylineHit first_hit_from(const Polyline& p, int j, double s, const Vec2& dir);

// The lowest vertex of each block, in Polyline::levels' layout: the pyramid the march under the
// profile skips by (built once per profile by whoever traces under it; a conductor never does).
struct PolylineLows {
  std::vector<std::vector<double>> levels;
};
PolylineLows polyline_lows(const Polyline& p);

// The same under the profile, for a ray travelling in the medium below it (the dielectric tracer's
// medium 2, sim/dielectric_polyline.h): entering from the bottom line y = y_min at x in
// [x_0, x_0 + period) along dir (unit, dir.y > 0), and leaving the point at parameter s of segment
// j along dir (unit), the segment excluded. Going down, a ray that passes below the lowest vertex
// has left (escaped); going up, it meets the profile within a period. lows = polyline_lows(p).
// Every operation is that of the march above the profile mirrored in y, so on the mirrored profile
// the hits are the same bit for bit.
PolylineHit first_hit_from_bottom(const Polyline& p, const PolylineLows& lows, double x, const Vec2& dir);
PolylineHit first_hit_from_below(const Polyline& p, const PolylineLows& lows, int j, double s, const Vec2& dir);

// 32 bytes, as sim::TraceResult.
struct PolylineTraceResult {
  Vec2 exit_dir = Vec2::Zero();  // valid when how == escaped
  int bounces = 0;
  int first_segment = -1;  // segment hit first; valid when bounces > 0
  Termination how = Termination::escaped;
};

struct NoPolylineObserver {
  void on_bounce(int /*segment*/, double /*s*/, const Vec2& /*dir_in*/) {}
};

// Traces one ray from the top line at x (in [x_0, x_0 + period)) along dir until it leaves, meets
// a vertex or reaches opt.max_bounces. The observer sees each reflection before it happens.
template <class Observer = NoPolylineObserver>
PolylineTraceResult trace_polyline(const Polyline& p, double x, const Vec2& dir, const TraceOptions& opt = {},
                                   Observer&& obs = Observer{}) {
  PolylineTraceResult r;
  Vec2 d = dir;
  PolylineHit h = first_hit_from_top(p, x, d);
  for (;;) {
    if (h.kind == PolylineHit::Kind::escaped) {
      r.exit_dir = d;
      r.how = Termination::escaped;
      return r;
    }
    if (h.kind == PolylineHit::Kind::vertex) {
      r.how = Termination::vertex_hit;
      return r;
    }
    if (r.bounces == opt.max_bounces) {
      r.how = Termination::bounce_limit;
      return r;
    }
    const Vec2& n = p.normal[static_cast<std::size_t>(h.segment)];
    const double dn = d.dot(n);
    // The ray crossed the segment from above, so d.n < 0 but for rounding when it runs along the
    // segment: the reflection is then undefined, as at a vertex.
    if (!(dn < 0.0)) [[unlikely]] {
      r.how = Termination::vertex_hit;
      return r;
    }
    obs.on_bounce(h.segment, h.s, d);
    d -= (2.0 * dn) * n;
    if (r.bounces == 0) r.first_segment = h.segment;
    ++r.bounces;
    h = first_hit_from(p, h.segment, h.s, d);
  }
}

}  // namespace vgroove::sim
