#include "vgroove/sim/dielectric_groove.h"

#include "vgroove/sim/dielectric_interaction.h"
#include "vgroove/sim/dielectric_lifted_law.h"

#include <cmath>
#include <cstdio>
#include <limits>
#include <stdexcept>
#include <string>

namespace vgroove::sim {

namespace {

std::string number_text(double v) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.17g", v);
  return buf;
}

bool is_facet(Part p) { return p == Part::left_facet || p == Part::right_facet; }

}  // namespace

const char* medium_name(Medium m) { return m == Medium::above ? "above" : "below"; }

double exit_angle(const DielectricExit& e) {
  return e.side == Medium::above ? std::atan2(-e.dir.x(), e.dir.y()) : std::atan2(e.dir.x(), -e.dir.y());
}

void DielectricResult::clear() {
  exits.clear();
  left[0] = left[1] = 0.0;
  cut = bounce_limit = vertex = 0.0;
  paths_cut = 0;
  interactions = 0;
  max_k = 0;
  pending.clear();
}

namespace detail {

void check_dielectric_options(const DielectricOptions& opt) {
  if (!(opt.eta > 0.0 && opt.eta < std::numeric_limits<double>::infinity()))
    throw std::invalid_argument("eta = " + number_text(opt.eta) + " is out of range (0, inf)");
  if (!(opt.min_weight >= 0.0 && opt.min_weight < 1.0))
    throw std::invalid_argument("min_weight = " + number_text(opt.min_weight) + " is out of range [0, 1)");
  if (opt.max_interactions < 0)
    throw std::invalid_argument("max_interactions = " + std::to_string(opt.max_interactions) +
                                " is out of range [0, 2147483647]");
}

void check_light_direction(const Vec2& dir, Medium from) {
  const double dy = dir.y();
  if (from == Medium::above ? !(dy < 0.0 && dy >= -1.0) : !(dy > 0.0 && dy <= 1.0))
    throw std::invalid_argument(
        "ray.dir.y = " + number_text(dy) + " is out of range " +
        (from == Medium::above ? "[-1, 0) for light from above" : "(0, 1] for light from below"));
}

}  // namespace detail

DielectricGrooveTracer::DielectricGrooveTracer(const Groove& g, const DielectricOptions& opt) : g_(g), opt_(opt) {
  detail::check_dielectric_options(opt);
}

bool DielectricGrooveTracer::first_from_above(const Ray2& ray, Pending& p, bool& vertex) const {
  // sim::trace's first hit, operation for operation, for rays through the opening; the flat parts
  // for the others (their crossing of the rim line is their hit).
  const double x_rim = ray.origin.x();
  const double x_l = g_.rim_x(Side::left), x_r = g_.rim_x(Side::right);
  if (!(x_rim > x_l && x_rim < x_r)) {
    if (x_rim < x_l || x_rim > x_r) {
      p.on = x_rim < x_l ? Part::left_flat : Part::right_flat;
      p.pos = x_rim;
      return true;
    }
    vertex = true;  // a rim exactly, or NaN
    return false;
  }
  Side on;
  double s = -1.0;
  if (!detail::first_facet_hit(g_, ray, on, s)) {  // met no facet: a vertex by rounding (as sim::trace)
    vertex = true;
    return false;
  }
  p.on = static_cast<Part>(on);
  p.pos = s;
  return true;
}

bool DielectricGrooveTracer::first_from_below(const Ray2& ray, Pending& p) const {
  // The line o + t d meets the interface first at its smallest t, whatever its sign: the light
  // comes from y = -inf. The flat parts lie on the rim line, met at t = 0 where the line crosses it
  // outside the opening; the facets where 0 <= u <= length for u = cross(o, d) / cross(e, d).
  const Vec2& o = ray.origin;
  const Vec2& d = ray.dir;
  double best_t = std::numeric_limits<double>::infinity();
  bool found = false;
  const double x_l = g_.rim_x(Side::left), x_r = g_.rim_x(Side::right);
  if (o.x() <= x_l || o.x() >= x_r) {
    best_t = 0.0;
    found = true;
    p.on = o.x() <= x_l ? Part::left_flat : Part::right_flat;
    p.pos = o.x();
  }
  for (int f = 0; f < 2; ++f) {
    const Facet& fa = g_.facet[f];
    const double den = cross(fa.edge, d);
    if (den == 0.0) continue;
    const double u = cross(o, d) / den;
    if (!(u >= 0.0 && u <= fa.length)) continue;
    const double t = cross(o, fa.edge) / den;
    if (t < best_t || !found) {
      best_t = t;
      found = true;
      p.on = static_cast<Part>(f);
      p.pos = u;
    }
  }
  return found;
}

bool DielectricGrooveTracer::advance(Part on, double pos, const Vec2& d, Medium medium, Pending& p) const {
  if (medium == Medium::above) {
    if (!is_facet(on)) return false;  // upward from the rim line: nothing above it
    // Inside the groove: sim::trace's step from facet to facet.
    if (!detail::step_to_other_facet(g_, static_cast<Side>(on), pos, d, p.pos)) return false;
    p.on = static_cast<Part>(1 - static_cast<int>(on));
    return true;
  }
  // Below: the nearest crossing with the other three parts, t > 0.
  const double H = g_.rim_height;
  const Vec2 o = is_facet(on) ? Vec2(pos * g_.facet[static_cast<int>(on)].edge) : Vec2(pos, H);
  double best_t = std::numeric_limits<double>::infinity();
  bool found = false;
  for (int f = 0; f < 2; ++f) {
    if (static_cast<int>(on) == f) continue;
    const Facet& fa = g_.facet[f];
    const double den = cross(fa.edge, d);
    if (den == 0.0) continue;
    const double t = cross(o, fa.edge) / den;
    if (!(t > 0.0 && t < best_t)) continue;
    const double u = cross(o, d) / den;
    if (!(u >= 0.0 && u <= fa.length)) continue;
    best_t = t;
    found = true;
    p.on = static_cast<Part>(f);
    p.pos = u;
  }
  if (d.y() != 0.0) {
    const double t = (H - o.y()) / d.y();
    if (t > 0.0 && t < best_t) {
      const double x = o.x() + t * d.x();
      const Part flat = x <= g_.rim_x(Side::left) ? Part::left_flat : Part::right_flat;
      if (flat != on && (x <= g_.rim_x(Side::left) || x >= g_.rim_x(Side::right))) {
        found = true;
        p.on = flat;
        p.pos = x;
      }
    }
  }
  return found;
}

DielectricResult& DielectricGrooveTracer::trace(const Ray2& ray, Medium from, Rng& rng, DielectricResult& out) const {
  return trace_with(ray, from, detail::FlatlandLaw{opt_.eta, 1.0 / opt_.eta, &opt_}, rng, out);
}

template <class Law>
DielectricResult& DielectricGrooveTracer::trace_with(const Ray2& ray, Medium from, const Law& law, Rng& rng,
                                                     DielectricResult& out) const {
  out.clear();
  detail::check_light_direction(ray.dir, from);
  Pending p0{ray.dir, 0.0, 1.0, 0, 0, Part::left_facet, from};
  bool vertex = false;
  const bool hit = from == Medium::above ? first_from_above(ray, p0, vertex) : first_from_below(ray, p0);
  if (!hit) {
    // Met nothing (a line through a vertex by rounding, or NaN): a vertex hit, never dropped.
    out.vertex = 1.0;
    return out;
  }
  const Part first = p0.on;
  const double x_l = g_.rim_x(Side::left), x_r = g_.rim_x(Side::right);
  const bool split = opt_.branching == Branching::split;
  std::vector<Pending>& pending = out.pending;
  pending.push_back(p0);
  while (!pending.empty()) {
    const Pending h = pending.back();
    pending.pop_back();
    const bool facet = is_facet(h.on);
    const Facet* fa = facet ? &g_.facet[static_cast<int>(h.on)] : nullptr;
    if (facet ? (h.pos == 0.0 || h.pos == fa->length) : h.pos == (h.on == Part::left_flat ? x_l : x_r)) {
      out.vertex += h.w;  // exactly on the apex or a rim: reflection and refraction undefined
      out.max_k = std::max(out.max_k, h.k);
      continue;
    }
    if (h.k == opt_.max_interactions) {
      out.bounce_limit += h.w;
      out.max_k = std::max(out.max_k, h.k);
      continue;
    }
    ++out.interactions;
    const Vec2 n = facet ? fa->normal : Vec2(0.0, 1.0);  // towards medium 1
    Vec2 t_dir = Vec2::Zero();
    const double F = law(h.d, n, h.in, t_dir);
    // The branches: reflected (weight w F, stays in its medium) and refracted (w (1 - F), crosses).
    double w_branch[2];
    detail::branch_weights(split, F, h.w, rng, w_branch);
    for (int b = 0; b < 2; ++b) {
      const double w = w_branch[b];
      if (!(w > 0.0)) continue;
      const int k = h.k + 1;
      if (w < opt_.min_weight) {
        out.cut += w;
        ++out.paths_cut;
        out.max_k = std::max(out.max_k, k);
        continue;
      }
      const Vec2 d = b == 0 ? (facet ? fa->reflect(h.d) : Vec2(h.d.x(), -h.d.y())) : t_dir;
      const Medium medium = b == 0 ? h.in : detail::other_medium(h.in);
      const std::uint64_t path = detail::branch_path(h.path, h.k, b);
      Pending next{d, 0.0, w, path, k, h.on, medium};
      if (advance(h.on, h.pos, d, medium, next)) {
        pending.push_back(next);
        continue;
      }
      out.add_exit(DielectricExit{d, w, path, k, medium, first});
    }
  }
  return out;
}

template DielectricResult& DielectricGrooveTracer::trace_with(const Ray2&, Medium, const detail::FlatlandLaw&, Rng&,
                                                              DielectricResult&) const;
template DielectricResult& DielectricGrooveTracer::trace_with(const Ray2&, Medium, const detail::LiftedLaw&, Rng&,
                                                              DielectricResult&) const;

}  // namespace vgroove::sim
