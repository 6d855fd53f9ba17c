// vgroove sim: exact 2D ray tracing inside one V-groove.
//
// Ground truth for the analytic model: explicit ray-segment intersections and mirror
// reflections in the real groove, never the kaleidoscopic unfolding. No epsilon offsets: after a
// reflection the facet just hit is excluded (a flat facet cannot be hit twice in a row), so a ray
// leaving a facet can only meet the other facet or leave through the opening.
#pragma once

#include "vgroove/sim/groove.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <vector>

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

// 32 bytes: the direction (16-byte aligned) first, so the small members share one padding.
struct TraceResult {
  Vec2 exit_dir = Vec2::Zero();  // valid when how == escaped
  int bounces = 0;
  Side first = Side::left;  // facet hit first; valid when bounces > 0
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
// The same test when sn = cross(p, d) and den = cross(e, d) are known and sn den >= 0.
inline double hit_facet_with(const Vec2& p, const Facet& f, double sn, double den) {
  if (den == 0.0 || cross(p, f.edge) * den < 0.0 || std::abs(sn) > f.length * std::abs(den)) return -1.0;
  return sn / den;
}
}  // namespace detail

namespace detail {
enum class Step : unsigned char { next, escaped, vertex_hit, bounce_limit };

// One reflection on facet f (the ray is at s e_f, travelling along d), then where it goes: onto
// the other facet o (s updated) or out through the opening. Facets are passed, not indexed, so
// the loop below runs with both facets fixed in registers.
template <class Observer>
[[gnu::always_inline]] inline Step bounce(Side on, const Facet& f, const Facet& o, Vec2& d, double& s, int& bounces,
                                          int max_bounces, Observer& obs) {
  if (s == 0.0 || s == f.length) return Step::vertex_hit;  // exactly on the apex or a rim
  if (bounces == max_bounces) return Step::bounce_limit;
  obs.on_bounce(on, d, f);
  d = f.reflect(d);
  ++bounces;
  const double den = cross(o.edge, d);
  if (!(den * f.turn_to_other > 0.0)) return Step::escaped;  // t <= 0: leaves through the opening
  const double c = cross(f.edge, d);
  // 0 <= s' <= length, tested without a division (s > 0, den != 0).
  if (c * den < 0.0 || s * std::abs(c) > o.length * std::abs(den)) return Step::escaped;  // passes the other facet
  s *= c / den;  // the ratio depends on the direction alone: off the position's dependency chain
  return Step::next;
}

// The reflections from facet `on` until the ray leaves, hits a vertex or reaches max_bounces,
// alternating between the facets, each with both facets fixed.
template <class Observer>
[[gnu::always_inline]] inline Step reflect_until_done(const Groove& g, Side on, Vec2& d, double& s, int& bounces,
                                                      int max_bounces, Observer& obs) {
  const Facet& fl = g[Side::left];
  const Facet& fr = g[Side::right];
  Step st;
  if (on == Side::right) goto on_right;
  for (;;) {
    st = bounce(Side::left, fl, fr, d, s, bounces, max_bounces, obs);
    if (st != Step::next) break;
  on_right:
    st = bounce(Side::right, fr, fl, d, s, bounces, max_bounces, obs);
    if (st != Step::next) break;
  }
  return st;
}

inline void finish(TraceResult& r, Step st, int bounces, const Vec2& d) {
  r.bounces = bounces;
  if (st == Step::escaped) [[likely]] {
    r.exit_dir = d;
    r.how = Termination::escaped;
  } else {
    r.how = st == Step::vertex_hit ? Termination::vertex_hit : Termination::bounce_limit;
  }
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
//
// The first hit: s = cross(p, d) / cross(e, d) for either facet, the numerator shared. Both
// facets are tested by signs and products; only the facet that answers is divided for (both
// answer only at the apex up to rounding, and then the nearer one, by t, is taken).
template <class Observer = NoBounceObserver>
[[gnu::always_inline]] inline TraceResult trace(const Groove& g, const Ray2& ray, const TraceOptions& opt = {},
                                                Observer&& obs = Observer{}) {
  TraceResult r;
  // Where the ray crosses the rim line decides whether it enters this groove at all.
  const double x_rim = ray.origin.x();
  const double x_l = g.rim_x(Side::left), x_r = g.rim_x(Side::right);
  if (!(x_rim > x_l && x_rim < x_r)) [[unlikely]] {
    if (x_rim < x_l || x_rim > x_r) {
      r.how = Termination::blocked;
      return r;
    }
    if (x_rim == x_l || x_rim == x_r) {
      r.how = Termination::vertex_hit;  // grazes a rim exactly
      return r;
    }
    // NaN: traced as any other ray (it meets no facet and is reported as a vertex hit)
  }
  const Facet& fl = g[Side::left];
  const Facet& fr = g[Side::right];
  Vec2 d = ray.dir;
  // First hit: either facet. The groove is convex, so a line entering the opening leaves it
  // through one facet; both answer only near the apex, and then the nearer one is hit.
  // s = cross(p, d) / cross(e, d) >= 0 for both facets needs the numerator's sign against each
  // denominator: when it excludes one facet (sn den < 0 is one of its miss tests), only the
  // other is tested in full; otherwise (sn = 0, or the ray runs more grazing than a facet) both.
  const double sn = cross(ray.origin, d);
  const double den_l = cross(fl.edge, d), den_r = cross(fr.edge, d);
  const bool away_l = sn * den_l < 0.0, away_r = sn * den_r < 0.0;
  Side on;
  double s;
  if (away_r & !away_l) [[likely]] {
    on = Side::left;
    s = detail::hit_facet_with(ray.origin, fl, sn, den_l);
  } else if (away_l & !away_r) [[likely]] {
    on = Side::right;
    s = detail::hit_facet_with(ray.origin, fr, sn, den_r);
  } else {
    const detail::FacetHit hl = detail::hit_facet_from_rim_line(ray.origin, d, fl);
    const detail::FacetHit hr = detail::hit_facet_from_rim_line(ray.origin, d, fr);
    if (hl.s >= 0.0 && (hr.s < 0.0 || hl.t_num / hl.t_den <= hr.t_num / hr.t_den))
      on = Side::left, s = hl.s;
    else
      on = Side::right, s = hr.s;
  }
  // s < 0 or NaN: entered the opening yet met no facet. Impossible for a closed groove, and
  // reported as a vertex hit (the only way is through a vertex by rounding) rather than dropped.
  if (!(s >= 0.0)) [[unlikely]] {
    r.how = Termination::vertex_hit;
    return r;
  }
  r.first = on;
  // The reflections, alternating between the facets, each with both facets fixed.
  detail::Step st;
  int bounces = 0;
  const int max_bounces = opt.max_bounces;
  if (on == Side::right) goto on_right;
  for (;;) {
    st = detail::bounce(Side::left, fl, fr, d, s, bounces, max_bounces, obs);
    if (st != detail::Step::next) break;
  on_right:
    st = detail::bounce(Side::right, fr, fl, d, s, bounces, max_bounces, obs);
    if (st != detail::Step::next) break;
  }
  r.bounces = bounces;
  if (st == detail::Step::escaped) [[likely]] {
    r.exit_dir = d;
    r.how = Termination::escaped;
  } else {
    r.how = st == detail::Step::vertex_hit ? Termination::vertex_hit : Termination::bounce_limit;
  }
  return r;
}

// The rays of one parallel beam in one groove: sim::trace for many rays of one direction.
//
// Everything sim::trace computes from the direction alone is computed once here, by the same
// operations in the same order: the first hit's denominators cross(e, d), and for each facet the
// ray may hit first, the directions after each reflection with their crossing tests
// (cross(e_o, d) against the turn, cross(e_f, d) against it) and ratios cross(e_f, d) /
// cross(e_o, d). Per ray only what depends on the position is left: s, its tests against the
// precomputed bounds and its products with the ratios. So every result (bounce count, first
// facet, termination, exit direction bit for bit) and every observer call is sim::trace's for
// the ray beam_ray(g, dir, x); the tests check that. Still ray-segment intersection in the real
// groove, step by step: the table is the ray's own sequence of directions, not an unfolding.
//
// Rays outside or at the ends of the opening are handed to sim::trace, rays past the table
// (more than kMaxTable reflections) to its reflection loop.
class BeamTracer {
 public:
  BeamTracer(const Groove& g, const Vec2& dir, const TraceOptions& opt = {});

  const Groove& groove() const { return g_; }
  const Vec2& dir() const { return dir_; }

  // sim::trace(groove(), beam_ray(groove(), dir(), x_rim), opt, obs).
  template <class Observer = NoBounceObserver>
  TraceResult trace(double x_rim, Observer&& obs = Observer{}) const;

  // out[j] = trace(x_rim[j], obs) for j < n, the observer called in the same order. Rays go in
  // blocks: a block's first hits and first reflections are computed together, without branches
  // (so the compiler vectorizes them); rays that reflect again go on one by one.
  template <class Observer = NoBounceObserver>
  void trace(const double* x_rim, long n, TraceResult* out, Observer&& obs = Observer{}) const;

  // Rays per block of the batch trace.
  static constexpr int kBlock = 256;

  // Reflections tabulated per first facet, at most this many (a 0.01 deg groove needs 18,000).
  static constexpr int kMaxTable = 1 << 15;

 private:
  // The first hit when the numerator's sign excludes neither facet (a beam more grazing than a
  // facet): both tested in full, as sim::trace. False when neither answers.
  bool first_hit_both(double x_rim, double sn, bool away_l, bool away_r, int& f, double& s) const;

  // The reflections of a ray whose first hit is at s e_f on facet f, as trace() goes on from there.
  template <class Observer>
  TraceResult reflect_from(int f, double s, Observer& obs) const;

  // What the batch trace knows of a block of rays after the first hit and first reflection:
  // path 0, the ray hit facet f and left after one reflection; path 1, it hit facet f at s and
  // reflects again; path 2, anything else (outside or at the ends of the opening, no facet met,
  // the apex or a rim hit, an empty table), for trace() to take from the start. 64-bit lanes,
  // for the vectorizer.
  struct BlockHits {
    double s[kBlock];
    std::int64_t f[kBlock];
    std::int64_t path[kBlock];
  };
  void first_hits(const double* x_rim, int n, BlockHits& h) const;

  // Reflection k (0-based) of a ray that hit facet `first` first: on facet first for even k,
  // on the other for odd k, leaving along d_out.
  struct Reflection {
    Vec2 d_out;
    double abs_c;  // |cross(e_f, d_out)|
    double limit;  // length_o |cross(e_o, d_out)|: past the other facet when s abs_c > limit
    double ratio;  // cross(e_f, d_out) / cross(e_o, d_out): s on the other facet is s ratio
    bool leaves;   // leaves whatever s: t <= 0, or the crossing on the far side of the apex
  };
  Groove g_;
  Vec2 dir_;
  TraceOptions opt_;
  double h_dx_;                       // rim_height dir.x, the position-free part of cross(p, dir)
  double den_[2];                     // cross(e_f, dir) per facet
  double h_ex_[2];                    // rim_height e_f.x, the position-free part of cross(p, e_f)
  double limit_[2];                   // length_f |den_f|
  std::vector<Reflection> table_[2];  // by first facet
};

template <class Observer>
[[gnu::always_inline]] inline TraceResult BeamTracer::trace(double x_rim, Observer&& obs) const {
  const double x_l = g_.rim_x(Side::left), x_r = g_.rim_x(Side::right);
  if (!(x_rim > x_l && x_rim < x_r)) [[unlikely]]
    return sim::trace(g_, Ray2{Vec2(x_rim, g_.rim_height), dir_}, opt_, obs);
  // cross(p, d) and cross(p, e) for p = (x_rim, rim_height), as sim::trace forms them.
  const double sn = x_rim * dir_.y() - h_dx_;
  const bool away_l = sn * den_[0] < 0.0, away_r = sn * den_[1] < 0.0;
  TraceResult r;
  int f;
  double s;
  if (away_r & !away_l) [[likely]]
    f = 0;
  else if (away_l & !away_r) [[likely]]
    f = 1;
  else
    f = -1;
  if (f >= 0) [[likely]] {
    // One facet excluded by the numerator's sign (the beam within the groove's aperture).
    const double den = den_[f];
    if (den == 0.0 || (x_rim * g_.facet[f].edge.y() - h_ex_[f]) * den < 0.0 || std::abs(sn) > limit_[f]) [[unlikely]] {
      r.how = Termination::vertex_hit;  // entered the opening yet met no facet (as sim::trace)
      return r;
    }
    s = sn / den;
  } else if (!first_hit_both(x_rim, sn, away_l, away_r, f, s)) {
    r.how = Termination::vertex_hit;
    return r;
  }
  if (!(s >= 0.0)) [[unlikely]] {
    r.how = Termination::vertex_hit;
    return r;
  }
  return reflect_from(f, s, obs);
}

template <class Observer>
[[gnu::always_inline]] inline TraceResult BeamTracer::reflect_from(int f, double s, Observer& obs) const {
  TraceResult r;
  const Side first = static_cast<Side>(f);
  const Facet& f0 = g_.facet[f];
  r.first = first;
  const Facet& f1 = g_.facet[1 - f];
  const std::vector<Reflection>& tab = table_[f];
  const int n = static_cast<int>(tab.size());
  int k = 0;
  for (;;) {
    const Facet& on = (k & 1) ? f1 : f0;
    if (s == 0.0 || s == on.length) [[unlikely]] {  // exactly on the apex or a rim
      detail::finish(r, detail::Step::vertex_hit, k, dir_);
      return r;
    }
    if (k == n) break;
    const Reflection& e = tab[k];
    obs.on_bounce((k & 1) ? other(first) : first, k ? tab[k - 1].d_out : dir_, on);
    ++k;
    if (e.leaves || s * e.abs_c > e.limit) {
      detail::finish(r, detail::Step::escaped, k, e.d_out);
      return r;
    }
    s *= e.ratio;
  }
  // Past the table: the bounce limit, or the reflection loop from here on.
  Vec2 d = n ? tab[n - 1].d_out : dir_;
  const detail::Step st =
      detail::reflect_until_done(g_, (k & 1) ? other(first) : first, d, s, k, opt_.max_bounces, obs);
  detail::finish(r, st, k, d);
  return r;
}

template <class Observer>
void BeamTracer::trace(const double* x_rim, long n, TraceResult* out, Observer&& obs) const {
  BlockHits h;
  for (long j0 = 0; j0 < n; j0 += kBlock) {
    const int m = static_cast<int>(std::min<long>(kBlock, n - j0));
    first_hits(x_rim + j0, m, h);
    for (int j = 0; j < m; ++j) {
      TraceResult& r = out[j0 + j];
      const int f = static_cast<int>(h.f[j]);
      if (h.path[j] == 0) [[likely]] {
        obs.on_bounce(static_cast<Side>(f), dir_, g_.facet[f]);
        r = TraceResult{};
        r.first = static_cast<Side>(f);
        detail::finish(r, detail::Step::escaped, 1, table_[f][0].d_out);
      } else if (h.path[j] == 1) {
        r = reflect_from(f, h.s[j], obs);
      } else {
        r = trace(x_rim[j0 + j], obs);
      }
    }
  }
}

}  // namespace vgroove::sim
