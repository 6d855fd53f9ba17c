// vgroove sim: exact 2D ray tracing over a periodic polyline height profile (sim/polyline.h).
//
// The same rules as the V-groove tracer (sim/tracer.h): explicit ray-segment intersections and
// mirror reflections, no epsilon offsets (after a reflection the segment just hit is excluded),
// and every ray ends in one of the Termination buckets: escaped, vertex_hit (a vertex met
// exactly, where the reflection is undefined), bounce_limit. `blocked` does not occur: a ray
// starts on the top line y = y_max above the whole profile.
//
// The first hit, watertight. A ray meets segment [a, b] when a and b lie on opposite sides of its
// line: sides cross(v - p, d) of opposite signs (a zero side is the ray through that vertex: a
// vertex hit). The profile is a height field, so a ray moving right (d.x > 0) can only meet the
// segments to the right of where it is, in the order of their x, and the first one whose end
// vertices' sides differ is the hit (moving left, the same leftwards). Each vertex's side is
// computed once per ray segment and shared by the two segments that meet at it, so a ray cannot
// slip between two segments through their common vertex by rounding. The hit parameter along the
// segment is side(a) / (side(a) - side(b)), in [0, 1] by construction; 0 or 1 is a vertex hit.
//
// Skipping. Before the segments of a block of the pyramid (sim/polyline.h), the ray is compared
// with the block's highest vertex at the block's end where the ray is lowest; if the vertex lies
// below the ray's line by more than the rounding of that comparison, no segment of the block can
// be met and the block is skipped (the margin only makes the skip conservative: whatever is not
// skipped is decided by the exact side test above). A ray going up leaves as soon as the highest
// vertex of the whole profile lies below it at the current x.
//
// Leaving. Moving up (or level), a ray that has passed one whole period without a hit never
// hits: over the next period it is higher by P tan(elevation) than over the last one, where it
// stayed above the profile, and the profile repeats. Moving down, a ray always hits within one
// period: the next copy of the highest vertex lies above it.
//
// Determinism: a ray's result depends only on the profile and the ray, never on other rays.
#pragma once

#include "vgroove/sim/polyline.h"
#include "vgroove/sim/tracer.h"

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
