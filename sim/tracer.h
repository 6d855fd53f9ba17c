// vgroove sim: exact 2D ray tracing inside one V-groove.
//
// Ground truth for the analytic model: explicit ray-segment intersections and mirror
// reflections in the real groove, never the kaleidoscopic unfolding. No epsilon offsets: after a
// reflection the facet just hit is excluded (a flat facet cannot be hit twice in a row), so a ray
// leaving a facet can only meet the other facet or leave through the opening.
#pragma once

#include "sim/groove.h"

#include <cmath>
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
// Where the ray p + t d meets the facet segment from the apex (origin) to its rim, s e with
// 0 <= s <= length. Crossing p + t d = s e with e and with d gives
//   t = cross(p, e) / cross(e, d),   s = cross(p, d) / cross(e, d).
// The tests compare signs and products, so the only division is the one that yields s for a
// hit. Returns s, or a negative value for a miss; `t_num`/`t_den` give t when both facets answer.
struct FacetHit {
  double s = -1.0;
  double t_num = 0.0, t_den = 1.0;
};
inline FacetHit hit_facet_from_rim_line(const Vec2& p, const Vec2& d, const Facet& f) {
  FacetHit h;
  const double den = cross(f.edge, d);
  if (den == 0.0) return h;  // parallel to the facet: no single crossing
  const double tn = cross(p, f.edge), sn = cross(p, d);
  // t >= 0: a flat groove's facets lie on the rim line itself, where the ray starts.
  if (tn * den < 0.0 || sn * den < 0.0 || std::abs(sn) > f.length * std::abs(den)) return h;
  h.s = sn / den;
  h.t_num = tn;
  h.t_den = den;
  return h;
}
}  // namespace detail

// Traces one ray from where it crosses the rim line. The observer sees every reflection; with
// the default observer the loop does nothing else.
//
// After the first hit the ray is on facet f at p = s e_f, and both facet lines pass through the
// apex, so the next crossing needs no position: with d the reflected direction and o the other
// facet,
//   s' = cross(p, d) / cross(e_o, d) = s * cross(e_f, d) / cross(e_o, d),
//   t  = cross(p, e_o) / cross(e_o, d) = s * cross(e_f, e_o) / cross(e_o, d),
// so t > 0 exactly when cross(e_o, d) has the sign of cross(e_f, e_o) (s > 0), and s' is s times
// a ratio of the direction alone: the position is a single number carried along the facets.
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
  Vec2 d = ray.dir;
  // First hit: either facet. The groove is convex, so a line entering the opening leaves it
  // through one facet; both answer only near the apex, and then the nearer one is hit.
  const detail::FacetHit hl = detail::hit_facet_from_rim_line(ray.origin, d, g[Side::left]);
  const detail::FacetHit hr = detail::hit_facet_from_rim_line(ray.origin, d, g[Side::right]);
  Side on;
  double s;
  if (hl.s >= 0.0 && (hr.s < 0.0 || hl.t_num / hl.t_den <= hr.t_num / hr.t_den)) {
    on = Side::left, s = hl.s;
  } else if (hr.s >= 0.0) {
    on = Side::right, s = hr.s;
  } else {
    // Entered the opening yet met no facet: impossible for a closed groove, and reported
    // as a vertex hit (the only way is through a vertex by rounding) rather than dropped.
    r.how = Termination::vertex_hit;
    return r;
  }
  r.first = on;
  for (;;) {
    const Facet& f = g[on];
    const Facet& o = g[other(on)];
    if (s == 0.0 || s == f.length) {  // exactly on the apex or a rim: reflection undefined
      r.how = Termination::vertex_hit;
      return r;
    }
    if (r.bounces == opt.max_bounces) {
      r.how = Termination::bounce_limit;
      return r;
    }
    obs.on_bounce(on, d, f);
    d = f.reflect(d);
    ++r.bounces;
    const double den = cross(o.edge, d);
    if (!(den * f.turn_to_other > 0.0)) break;  // t <= 0: leaves through the opening
    const double c = cross(f.edge, d);
    // 0 <= s' <= length, tested without a division (s > 0, den != 0).
    if (c * den < 0.0 || s * std::abs(c) > o.length * std::abs(den)) break;  // passes the other facet
    s *= c / den;  // the ratio depends on the direction alone: off the position's dependency chain
    on = other(on);
  }
  r.exit_dir = d;
  r.how = Termination::escaped;
  return r;
}

}  // namespace vgroove::sim
