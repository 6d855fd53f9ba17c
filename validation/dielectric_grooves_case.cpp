#include "vgroove/validation/dielectric_grooves_case.h"

#include "vgroove/sim/beam.h"
#include "vgroove/sim/dielectric_groove.h"
#include "vgroove/sim/dielectric_microsurface.h"
#include "vgroove/sim/microsurface.h"
#include "vgroove/sim/zones.h"

#include <algorithm>
#include <bit>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <limits>
#include <numbers>
#include <set>
#include <stdexcept>
#include <string>

namespace vgroove::validation {

namespace {

// A facet whose projected width is below this fraction of its length is not lit (as groove_case.cpp).
constexpr double kMinProjectedWidth = 1e-12;

std::string number_text(double v) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.17g", v);
  return buf;
}

sim::DielectricOptions split_options(double eta, int max_interactions) {
  sim::DielectricOptions o;
  o.eta = eta;
  o.branching = sim::Branching::split;
  o.min_weight = 0.0;  // every path of positive weight followed to its end
  o.max_interactions = max_interactions;
  return o;
}

// The hit of interaction j (1-based) at which a path first refracted: its lowest set bit + 1.
int first_refraction(std::uint64_t path) { return std::countr_zero(path) + 1; }

// The outcome that fixes a ray's split tree: the part met first and the chain's hit count n in
// medium 1 (the largest hit of a pure R exit or of a first refraction), encoded as a conductor
// TraceResult so that sim::find_zones searches it: blocked (a flat part first), vertex_hit (any
// weight on a vertex), else escaped with first and bounces = n.
sim::TraceResult outcome_of(const sim::DielectricResult& r) {
  sim::TraceResult t;
  if (r.vertex > 0.0 || r.exits.empty()) {
    t.how = sim::Termination::vertex_hit;
    return t;
  }
  const sim::Part first = r.exits.front().first;
  if (first == sim::Part::left_flat || first == sim::Part::right_flat) {
    t.how = sim::Termination::blocked;
    return t;
  }
  int n = 0;
  for (const sim::DielectricExit& e : r.exits) n = std::max(n, e.path == 0 ? e.k : first_refraction(e.path));
  t.how = sim::Termination::escaped;
  t.first = static_cast<Side>(first);
  t.bounces = n;
  return t;
}

double wrapped_difference(double a, double b) { return std::abs(std::remainder(a - b, 2.0 * std::numbers::pi)); }

// Light from below: the outcome that fixes a ray's split tree, as outcome_of: the part met first and
// the chain's hit count n in medium 1 (hit 0 is the facet met first; a path refracted there and
// leaving after k interactions made k - 1 hits, one refracted again made that hit's index).
sim::TraceResult outcome_below(const sim::DielectricResult& r) {
  sim::TraceResult t;
  if (r.vertex > 0.0 || r.exits.empty()) {
    t.how = sim::Termination::vertex_hit;
    return t;
  }
  const sim::Part first = r.exits.front().first;
  if (first == sim::Part::left_flat || first == sim::Part::right_flat) {
    t.how = sim::Termination::blocked;
    return t;
  }
  int n = 0;
  for (const sim::DielectricExit& e : r.exits) {
    if ((e.path & 1u) == 0) continue;
    const std::uint64_t rest = e.path & ~std::uint64_t{1};
    n = std::max(n, rest == 0 ? e.k - 1 : std::countr_zero(rest));
  }
  t.how = sim::Termination::escaped;
  t.first = static_cast<Side>(first);
  t.bounces = n;
  return t;
}

std::map<BelowSignature, analytic::BelowLobe> lobes_by_signature(const analytic::DielectricBelowPrediction& m) {
  std::map<BelowSignature, analytic::BelowLobe> out;
  for (const analytic::BelowLobe& l : m.lobes) {
    analytic::BelowLobe& o = out[{l.path, l.k, l.up}];
    o.theta = l.theta;
    o.share += l.share;
  }
  return out;
}

}  // namespace

void check_dielectric_groove_case(const DielectricGrooveCase& c) {
  const double min_theta_v = kMinComparedApertureDeg * std::numbers::pi / 180.0;
  if (!(c.theta_v >= min_theta_v && c.theta_v <= std::numbers::pi))
    throw std::invalid_argument("theta_v = " + number_text(c.theta_v) + " rad is out of range [" +
                                number_text(min_theta_v) +
                                ", pi] (6 deg: the tracer's path signatures hold 64 interactions)");
  if (!(std::abs(c.theta_i) < 0.5 * std::numbers::pi))
    throw std::invalid_argument("theta_i = " + number_text(c.theta_i) + " rad is out of range (-pi/2, pi/2)");
  if (!(c.eta > 0.0 && c.eta < std::numeric_limits<double>::infinity()))
    throw std::invalid_argument("eta = " + number_text(c.eta) + " is out of range (0, inf)");
}

namespace {
// The breakpoint search over the rays aimed at `side`'s facet, light entering from `from` along
// `dir`, outcomes by `outcome`: each zone's inner ray traced once (its weights hold across the zone,
// KD-4) and its exits given to visit(share, result). Zones of vertex hits count as lost, zones
// meeting a flat part first as flat; from below, a zone meeting the other facet first (a sliver at
// the apex line, by rounding) as lost.
template <class Visit>
void trace_zones(const DielectricGrooveCase& c, Side side, long grid, int max_interactions, sim::Medium from,
                 const sim::Vec2& dir, sim::TraceResult (*outcome)(const sim::DielectricResult&), ZoneSearchCounts& out,
                 Visit&& visit) {
  const sim::Groove g = sim::make_symmetric_groove(c.theta_v);
  // The lines of the rays aimed at the facet are those of light from above at theta_i (sim/beam.h).
  const sim::Interval aim = sim::aimed_at(g, c.theta_i, side);
  if (!(aim.width() > 0.0)) return;
  out.lit = true;
  const sim::DielectricGrooveTracer tracer(g, split_options(c.eta, max_interactions));
  sim::Rng unused(0, 0, 0);
  sim::DielectricResult r;
  auto trace = [&](double x) -> const sim::DielectricResult& {
    tracer.trace(sim::beam_ray(g, dir, x), from, unused, r);
    ++out.traced;
    out.interactions += r.interactions;
    out.conservation = std::max(out.conservation, std::abs(1.0 - r.total()));
    return r;
  };
  const sim::ZoneSearch zs = sim::find_zones(
      aim, grid,
      [&](const double* x, int n, sim::TraceResult* o) {
        for (int q = 0; q < n; ++q) o[q] = outcome(trace(x[q]));
      },
      [&](double x) { return outcome(trace(x)); }, sim::lemma_covers, [](double, const sim::TraceResult&) {});
  out.uncertified_cells = zs.uncertified_cells;
  out.missed_bound = zs.missed_bound() / aim.width();
  const sim::TraceResult* last = nullptr;
  for (const sim::Zone& z : zs.zones) {
    const double share = z.width() / aim.width();
    if (z.ray.how == sim::Termination::vertex_hit) {
      out.lost += share;
      continue;
    }
    if (last == nullptr || !sim::same_outcome(*last, z.ray)) ++out.zones;
    last = &z.ray;
    if (z.ray.how == sim::Termination::blocked) {
      out.flat += share;
      continue;
    }
    if (from == sim::Medium::below && z.ray.first != side) {
      out.lost += share;
      continue;
    }
    const sim::DielectricResult& t = trace(z.lo + 0.5 * (z.hi - z.lo));
    out.lost += share * (t.cut + t.bounce_limit + t.vertex);
    for (const sim::DielectricExit& e : t.exits) {
      if (!std::isfinite(share * e.weight) || !e.dir.allFinite()) out.non_finite = true;
      visit(share, e);
    }
  }
}
}  // namespace

TracedFacetEnergy trace_facet_energy(const DielectricGrooveCase& c, Side side, long grid, int max_interactions) {
  TracedFacetEnergy out;
  trace_zones(c, side, grid, max_interactions, sim::Medium::above, sim::beam_direction(c.theta_i), outcome_of, out,
              [&](double share, const sim::DielectricExit& e) {
                const double w = share * e.weight;
                if (e.path == 0) {
                  out.reflected[e.k] += w;
                  out.reflected_theta_o[e.k] = sim::exit_angle(e);
                  return;
                }
                const int j = first_refraction(e.path);
                out.refracted[j] += w;
                if (e.k == j && e.side == sim::Medium::below) {
                  out.direct[j] += w;
                  out.direct_theta_t[j] = sim::exit_angle(e);
                } else if (j < 64 && (e.path >> j & 1u) != 0) {
                  out.recross[j] += w;
                }
              });
  return out;
}

DielectricFacetOutcome compare_facet(const analytic::DielectricFacetPrediction& m, const TracedFacetEnergy& t) {
  DielectricFacetOutcome o;
  // A facet whose projected width is below kMinProjectedWidth gets a beam too thin to place rays
  // in: not compared (as groove_case.cpp). Otherwise a lit model facet with no traced rays is a miss.
  if (!m.lit || m.f_a < kMinProjectedWidth) return o;
  if (!t.lit) {
    o.compared = true;
    o.l1 = 1.0;
    return o;
  }
  o.compared = true;
  o.k = m.k, o.f_a = m.f_a, o.shadow = m.shadow;
  o.zones = t.zones, o.traced = t.traced, o.interactions = t.interactions;
  o.uncertified_cells = t.uncertified_cells, o.missed_bound = t.missed_bound, o.conservation = t.conservation;
  o.reflected = m.reflected_total(), o.transmitted = m.transmitted_total();
  double l1 = std::abs(t.flat - m.shadow) + t.lost;
  // R chains by n.
  std::map<int, double> model_r;
  std::map<int, double> model_theta_o;
  for (const analytic::ReflectedLobe* r : {&m.fewer, &m.more}) {
    if (r->G <= 0.0) continue;
    model_r[r->n] += r->share;
    model_theta_o[r->n] = r->theta_o;
  }
  std::set<int> ns;
  for (const auto& [n, v] : model_r) ns.insert(n);
  for (const auto& [n, v] : t.reflected) ns.insert(n);
  for (int n : ns) {
    const auto a = t.reflected.find(n);
    const auto b = model_r.find(n);
    l1 += std::abs((a == t.reflected.end() ? 0.0 : a->second) - (b == model_r.end() ? 0.0 : b->second));
    if (a != t.reflected.end() && model_theta_o.count(n) != 0)
      o.direction_error =
          std::max(o.direction_error, wrapped_difference(t.reflected_theta_o.at(n), model_theta_o.at(n)));
  }
  // Refracted lobes by j: every path refracted first at j, and those that left at once.
  std::map<int, const analytic::TransmittedLobe*> lobes;
  for (const analytic::TransmittedLobe& l : m.transmitted) lobes[l.j] = &l;
  std::set<int> js;
  for (const auto& [j, l] : lobes) js.insert(j);
  for (const auto& [j, v] : t.refracted) js.insert(j);
  for (int j : js) {
    const auto it = lobes.find(j);
    const analytic::TransmittedLobe* l = it == lobes.end() ? nullptr : it->second;
    const double share = l ? l->share : 0.0;
    const auto a = t.refracted.find(j);
    const auto d = t.direct.find(j);
    const double traced_all = a == t.refracted.end() ? 0.0 : a->second;
    const double traced_direct = d == t.direct.end() ? 0.0 : d->second;
    l1 += std::abs(traced_all - share);
    l1 += std::abs(traced_direct - (l && l->direct ? share : 0.0));
    o.unknown += traced_all - traced_direct;
    const auto rc = t.recross.find(j);
    if (rc != t.recross.end()) o.unknown_recross += rc->second;
    if (l && !l->direct) o.unknown_model += share;
    if (d != t.direct.end() && l && !l->tir)
      o.direction_error = std::max(o.direction_error, wrapped_difference(t.direct_theta_t.at(j), l->theta_t));
  }
  o.l1 = l1;
  return o;
}

double prediction_distance(const analytic::DielectricFacetPrediction& a, const analytic::DielectricFacetPrediction& b,
                           double& dir) {
  dir = 0.0;
  if (a.lit != b.lit) return 1.0;
  if (!a.lit) return 0.0;
  double d = std::abs(a.shadow - b.shadow);
  std::map<int, double> r;
  for (const analytic::ReflectedLobe* l : {&a.fewer, &a.more}) r[l->n] += l->share;
  for (const analytic::ReflectedLobe* l : {&b.fewer, &b.more}) r[l->n] -= l->share;
  for (const auto& [n, v] : r) d += std::abs(v);
  const std::size_t m = std::max(a.transmitted.size(), b.transmitted.size());
  for (std::size_t q = 0; q < m; ++q) {
    const analytic::TransmittedLobe* x = q < a.transmitted.size() ? &a.transmitted[q] : nullptr;
    const analytic::TransmittedLobe* y = q < b.transmitted.size() ? &b.transmitted[q] : nullptr;
    d += std::abs((x ? x->share : 0.0) - (y ? y->share : 0.0));
    if (x && y && !x->tir && !y->tir) dir = std::max(dir, wrapped_difference(x->theta_t, y->theta_t));
  }
  if (a.fewer.n == b.fewer.n) dir = std::max(dir, wrapped_difference(a.fewer.theta_o, b.fewer.theta_o));
  return d;
}

double rounding_bound(const DielectricGrooveCase& c, Side side, double& dir) {
  const analytic::DielectricFacetPrediction m = analytic::kaleidoscope_dielectric(c.theta_i, c.theta_v, c.eta, side);
  double bound = 0.0;
  dir = 0.0;
  for (double sign : {-1.0, 1.0}) {
    double d = 0.0;
    const analytic::DielectricFacetPrediction p =
        analytic::kaleidoscope_dielectric(c.theta_i + sign * kRoundingAngle, c.theta_v, c.eta, side);
    bound = std::max(bound, prediction_distance(m, p, d));
    dir = std::max(dir, d);
  }
  return bound;
}

TracedBelowEnergy trace_facet_energy_below(const DielectricGrooveCase& c, Side side, long grid, int max_interactions) {
  TracedBelowEnergy out;
  // Light from below travels up along direction_at(theta_i), on the lines of light from above.
  trace_zones(c, side, grid, max_interactions, sim::Medium::below, sim::direction_at(c.theta_i), outcome_below, out,
              [&](double share, const sim::DielectricExit& e) {
                const BelowSignature key{e.path, e.k, e.side == sim::Medium::above};
                out.energy[key] += share * e.weight;
                out.theta[key] = sim::exit_angle(e);
              });
  return out;
}

DielectricFacetOutcome compare_facet_below(const analytic::DielectricBelowPrediction& m, const TracedBelowEnergy& t) {
  DielectricFacetOutcome o;
  if (!m.lit || m.f_a < kMinProjectedWidth) return o;
  o.compared = true;
  if (!t.lit) {
    o.l1 = 1.0;
    return o;
  }
  o.k = m.n_max, o.f_a = m.f_a;
  o.zones = t.zones, o.traced = t.traced, o.interactions = t.interactions;
  o.uncertified_cells = t.uncertified_cells, o.missed_bound = t.missed_bound, o.conservation = t.conservation;
  o.reflected = m.reflected_total(), o.transmitted = m.transmitted_total();
  const std::map<BelowSignature, analytic::BelowLobe> model = lobes_by_signature(m);
  double l1 = t.flat + t.lost;
  for (const auto& [key, e] : t.energy) {
    const auto it = model.find(key);
    l1 += std::abs(e - (it == model.end() ? 0.0 : it->second.share));
    if (it != model.end() && e > 0.0)
      o.direction_error = std::max(o.direction_error, wrapped_difference(t.theta.at(key), it->second.theta));
  }
  for (const auto& [key, l] : model)
    if (t.energy.count(key) == 0) l1 += std::abs(l.share);
  o.l1 = l1;
  return o;
}

double prediction_distance_below(const analytic::DielectricBelowPrediction& a,
                                 const analytic::DielectricBelowPrediction& b, double& dir) {
  dir = 0.0;
  if (a.lit != b.lit) return 1.0;
  if (!a.lit) return 0.0;
  const std::map<BelowSignature, analytic::BelowLobe> la = lobes_by_signature(a), lb = lobes_by_signature(b);
  double d = 0.0;
  for (const auto& [key, l] : la) {
    const auto it = lb.find(key);
    d += std::abs(l.share - (it == lb.end() ? 0.0 : it->second.share));
    if (it != lb.end()) dir = std::max(dir, wrapped_difference(l.theta, it->second.theta));
  }
  for (const auto& [key, l] : lb)
    if (la.count(key) == 0) d += std::abs(l.share);
  return d;
}

double rounding_bound_below(const DielectricGrooveCase& c, Side side, double& dir) {
  const analytic::DielectricBelowPrediction m =
      analytic::kaleidoscope_dielectric_below(c.theta_i, c.theta_v, c.eta, side);
  double bound = 0.0;
  dir = 0.0;
  for (double sign : {-1.0, 1.0}) {
    double d = 0.0;
    const analytic::DielectricBelowPrediction p =
        analytic::kaleidoscope_dielectric_below(c.theta_i + sign * kRoundingAngle, c.theta_v, c.eta, side);
    bound = std::max(bound, prediction_distance_below(m, p, d));
    dir = std::max(dir, d);
  }
  return bound;
}

namespace {

// The periodic surface of the case's groove: the unknown shares of stratified rays over the opening.
void measure_surface(const DielectricGrooveCase& c, const DielectricCaseOptions& opt, DielectricCaseOutcome& out) {
  sim::Microsurface s;
  s.options.grooves = 1;
  s.theta_m.push_back(0.5 * (std::numbers::pi - c.theta_v));
  s.grooves.push_back(sim::make_symmetric_groove(c.theta_v));
  sim::DielectricOptions o = split_options(c.eta, opt.max_interactions);
  o.min_weight = opt.surface_min_weight;
  const sim::DielectricSurfaceTracer tracer(s, o);
  const sim::Groove& g = s.grooves.front();
  const sim::Interval open = sim::opening(g);
  const sim::Vec2 dir = sim::beam_direction(c.theta_i);
  sim::Rng unused(0, 0, 0);
  sim::DielectricResult r;
  const double w_ray = 1.0 / static_cast<double>(opt.surface_rays);
  for (long q = 0; q < opt.surface_rays; ++q) {
    const double x = sim::sample_position(sim::Sampling::stratified, open, q, opt.surface_rays, unused);
    tracer.trace_from_above(0, sim::beam_ray(g, dir, x), unused, r);
    out.interactions += r.interactions;
    out.surface_cut += w_ray * (r.cut + r.bounce_limit + r.vertex);
    for (const sim::DielectricExit& e : r.exits) {
      if (e.path == 0) continue;
      const int j = first_refraction(e.path);
      if (e.k == j) continue;
      out.surface_unknown += w_ray * e.weight;
      if (j < 64 && (e.path >> j & 1u) != 0) out.surface_recross += w_ray * e.weight;
    }
  }
  out.surface_rays = opt.surface_rays;
  out.rays += opt.surface_rays;
}

}  // namespace

DielectricCaseOutcome run_dielectric_groove_case(const DielectricGrooveCase& c, const DielectricCaseOptions& opt,
                                                 const std::atomic<bool>* cancel) {
  check_dielectric_groove_case(c);
  const auto t0 = std::chrono::steady_clock::now();
  DielectricCaseOutcome out;
  out.c = c;
  double entering = 0.0;
  for (Side s : {Side::left, Side::right}) {
    if (cancel && cancel->load(std::memory_order_relaxed)) return out;
    DielectricFacetOutcome& f = out.facet[static_cast<int>(s)];
    if (c.below) {
      // Light from below: every path class by signature; nothing left unknown with flat rims.
      const analytic::DielectricBelowPrediction m =
          analytic::kaleidoscope_dielectric_below(c.theta_i, c.theta_v, c.eta, s);
      const TracedBelowEnergy t = trace_facet_energy_below(c, s, opt.grid, opt.max_interactions);
      f = compare_facet_below(m, t);
      out.non_finite = out.non_finite || t.non_finite || !std::isfinite(f.l1) || !std::isfinite(f.direction_error);
      out.rays += t.traced;
      out.interactions += t.interactions;
      out.l1 = std::max(out.l1, f.l1);
      out.direction_error = std::max(out.direction_error, f.direction_error);
      out.conservation = std::max(out.conservation, f.conservation);
      out.missed_bound = std::max(out.missed_bound, f.missed_bound);
      if (!f.compared) continue;
      double dir_bound = 0.0;
      out.l1_bound = std::max(out.l1_bound, rounding_bound_below(c, s, dir_bound));
      out.direction_bound = std::max(out.direction_bound, dir_bound);
      entering += f.f_a;  // the facet's width across the beam; all of it is lit
      out.reflected += f.f_a * f.reflected;
      out.transmitted += f.f_a * f.transmitted;
      continue;
    }
    const analytic::DielectricFacetPrediction m = analytic::kaleidoscope_dielectric(c.theta_i, c.theta_v, c.eta, s);
    const TracedFacetEnergy t = trace_facet_energy(c, s, opt.grid, opt.max_interactions);
    f = compare_facet(m, t);
    out.non_finite = out.non_finite || t.non_finite || !std::isfinite(f.l1) || !std::isfinite(f.direction_error);
    out.rays += t.traced;
    out.interactions += t.interactions;
    out.l1 = std::max(out.l1, f.l1);
    out.direction_error = std::max(out.direction_error, f.direction_error);
    out.conservation = std::max(out.conservation, f.conservation);
    out.missed_bound = std::max(out.missed_bound, f.missed_bound);
    if (!f.compared || !m.lit) continue;
    double dir_bound = 0.0;
    out.l1_bound = std::max(out.l1_bound, rounding_bound(c, s, dir_bound));
    out.direction_bound = std::max(out.direction_bound, dir_bound);
    // Shares of the facet's rays -> of the rays entering the opening: weights f_a.
    entering += f.f_a * (1.0 - f.shadow);
    out.unknown += f.f_a * f.unknown;
    out.unknown_model += f.f_a * f.unknown_model;
    out.unknown_recross += f.f_a * f.unknown_recross;
    out.reflected += f.f_a * f.reflected;
    out.transmitted += f.f_a * f.transmitted;
  }
  if (entering > 0.0)
    for (double* v : {&out.unknown, &out.unknown_model, &out.unknown_recross, &out.reflected, &out.transmitted})
      *v /= entering;
  // The periodic surface is measured for light from above only (from below it is the model at 1/eta,
  // KaleidoscopeDielectricFromBelow.*).
  if (!c.below && opt.surface_rays > 0 && !(cancel && cancel->load(std::memory_order_relaxed)))
    measure_surface(c, opt, out);
  out.wall_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  return out;
}

}  // namespace vgroove::validation
