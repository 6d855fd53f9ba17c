// vgroove sim: exact 2D ray tracing inside one V-groove.
//
// Ground truth for the analytic model: explicit ray-segment intersections and mirror
// reflections in the real groove, never the kaleidoscopic unfolding. No epsilon offsets: after a
// reflection the facet just hit is excluded (a flat facet cannot be hit twice in a row), so a ray
// leaving a facet can only meet the other facet or leave through the opening.
#pragma once

#include "sim/groove.h"

#include <cstdint>

namespace vgroove::sim {

struct Ray2 {
  Vec2 origin;  // where the ray crosses the rim line (origin.y == rim_height)
  Vec2 dir;     // unit, pointing down into the groove (dir.y < 0)
};

enum class Termination : unsigned char {
  escaped,       // left through the opening going up
  blocked,       // never entered the opening (it meets the surface outside this groove)
  vertex_hit,    // hit the apex or a rim exactly: reflection undefined
  bounce_limit,  // still inside after TraceOptions::max_bounces reflections
};
const char* termination_name(Termination t);

struct TraceOptions {
  int max_bounces = 100000;
};

struct TraceResult {
  int bounces = 0;
  Vec2 exit_dir = Vec2::Zero();  // valid when how == escaped
  Side first = Side::left;       // facet hit first; valid when bounces > 0
  Termination how = Termination::escaped;
};

// Does nothing: the tracer's default observer, compiled away.
struct NoBounceObserver {
  void on_bounce(Side, const Vec2& /*dir_in*/, const Facet&) {}
};

namespace detail {
// Ray against the facet segment from the apex (origin) to its rim: p + t d = s e.
// Returns the segment parameter s when the ray meets the segment ahead (t > 0; t >= 0 from the
// rim line, where a flat groove's facets lie), else a negative value.
// Crossing with e and d gives s = cross(p, d) / cross(e, d), t = cross(p, e) / cross(e, d).
inline double hit_facet(const Vec2& p, const Vec2& d, const Facet& f, bool from_rim_line = false,
                        double* t_out = nullptr) {
  const double denom = cross(f.edge, d);
  if (denom == 0.0) return -1.0;  // parallel to the facet: no single crossing
  const double t = cross(p, f.edge) / denom;
  if (t_out) *t_out = t;
  const double s = cross(p, d) / denom;
  if (t < 0.0 || (t == 0.0 && !from_rim_line) || s < 0.0 || s > f.length) return -1.0;
  return s;
}
}  // namespace detail

// Traces one ray from where it crosses the rim line. The observer sees every reflection; with
// the default observer the loop does nothing else.
template <class Observer = NoBounceObserver>
TraceResult trace(const Groove& g, const Ray2& ray, const TraceOptions& opt = {},
                  Observer&& obs = Observer{}) {
  TraceResult r;
  // Where the ray crosses the rim line decides whether it enters this groove at all.
  const double x_rim = ray.origin.x();
  if (x_rim < g.rim_x(Side::left) || x_rim > g.rim_x(Side::right)) {
    r.how = Termination::blocked;
    return r;
  }
  if (x_rim == g.rim_x(Side::left) || x_rim == g.rim_x(Side::right)) {
    r.how = Termination::vertex_hit;  // grazes a rim exactly
    return r;
  }
  Vec2 p = ray.origin;
  Vec2 d = ray.dir;
  // First hit: either facet. The groove is convex, so a line entering the opening leaves it
  // through one facet; both answer only near the apex, and then the nearer one is hit.
  double tl = 0.0, tr = 0.0;
  const double sl = detail::hit_facet(p, d, g[Side::left], true, &tl);
  const double sr = detail::hit_facet(p, d, g[Side::right], true, &tr);
  Side on;
  double s;
  if (sl >= 0.0 && (sr < 0.0 || tl <= tr)) {
    on = Side::left, s = sl;
  } else if (sr >= 0.0) {
    on = Side::right, s = sr;
  } else {
    // Entered the opening yet met no facet: impossible for a closed groove, and reported
    // as a vertex hit (the only way is through a vertex by rounding) rather than dropped.
    r.how = Termination::vertex_hit;
    return r;
  }
  r.first = on;
  for (;;) {
    const Facet& f = g[on];
    if (s == 0.0 || s == f.length) {  // exactly on the apex or a rim: reflection undefined
      r.how = Termination::vertex_hit;
      return r;
    }
    if (r.bounces == opt.max_bounces) {
      r.how = Termination::bounce_limit;
      return r;
    }
    obs.on_bounce(on, d, f);
    p = s * f.edge;  // on the facet line by construction: no drift off the surface
    d = reflect(d, f.normal);
    ++r.bounces;
    on = other(on);
    s = detail::hit_facet(p, d, g[on]);
    if (s < 0.0) break;  // misses the other facet: leaves through the opening
  }
  r.exit_dir = d;
  r.how = Termination::escaped;
  return r;
}

}  // namespace vgroove::sim
