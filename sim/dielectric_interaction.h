// vgroove sim: one hit of a path on a dielectric interface, shared by the dielectric tracers
// (sim/dielectric_groove.h, sim/dielectric_microsurface.h): the reflected share F at the local
// angle and the refracted direction, and the checks of the tracers' options.
#pragma once

#include "vgroove/optics/fresnel.h"
#include "vgroove/optics/snell.h"
#include "vgroove/sim/dielectric_groove.h"
#include "vgroove/sim/tracer.h"

#include <cmath>
#include <cstdint>

namespace vgroove::sim::detail {

inline Medium other_medium(Medium m) { return m == Medium::above ? Medium::below : Medium::above; }

// The two branches of a hit of weight w with reflected share F: [0] reflected, [1] refracted.
// Splitting gives each its share; the random choice gives all of w to one, reflected with
// probability F (drawn from rng only where F < 1).
inline void branch_weights(bool split, double F, double w, Rng& rng, double out[2]) {
  if (split) {
    out[0] = w * F;
    out[1] = w * (1.0 - F);
    return;
  }
  const bool reflect = F >= 1.0 || rng.uniform() < F;
  out[0] = reflect ? w : 0.0;
  out[1] = reflect ? 0.0 : w;
}

// A path's R/T signature after branch b at its k-th interaction (bit k set for a refraction; the
// first 64 interactions recorded).
inline std::uint64_t branch_path(std::uint64_t path, int k, int b) {
  return path | (b == 1 && k < 64 ? std::uint64_t{1} << k : 0);
}

// A path along d in medium `in` meets a part of unit normal n (towards medium 1). Returns F, the
// reflected share (1 under total internal reflection and in the conductor limit), and sets t to
// the refracted direction when F < 1. eta = n2 / n1, inv_eta = 1 / eta.
inline double fresnel_split(const Vec2& d, const Vec2& n, Medium in, double eta, double inv_eta,
                            const DielectricOptions& opt, Vec2& t) {
  const double eta_rel = in == Medium::above ? eta : inv_eta;
  const Vec2 m = in == Medium::above ? n : Vec2(-n);  // the normal on the incident side
  if (opt.conductor_limit || !optics::refract(d, m, eta_rel, t)) return 1.0;
  const double cos_i = std::abs(d.dot(n));
  switch (opt.polarization) {
    case Polarization::s:
      return optics::fresnel_dielectric_polarized(cos_i, eta_rel).s;
    case Polarization::p:
      return optics::fresnel_dielectric_polarized(cos_i, eta_rel).p;
    case Polarization::unpolarized:
      break;
  }
  return optics::fresnel_dielectric(cos_i, eta_rel);
}

// The flatland law of a hit: fresnel_split with the options' eta (the tracers' trace_with law; the
// lifted 3D law is sim/dielectric_lifted_law.h's LiftedLaw).
struct FlatlandLaw {
  double eta, inv_eta;
  const DielectricOptions* opt;
  double operator()(const Vec2& d, const Vec2& n, Medium in, Vec2& t) const {
    return fresnel_split(d, n, in, eta, inv_eta, *opt, t);
  }
};

// sim::trace's first hit, operation for operation, of a ray crossing the rim line inside the
// opening: the facet `on` and s along it. False when it meets no facet (a vertex by rounding, as
// sim::trace reports it).
inline bool first_facet_hit(const Groove& g, const Ray2& ray, Side& on, double& s) {
  const Facet& fl = g[Side::left];
  const Facet& fr = g[Side::right];
  const Vec2& d = ray.dir;
  const double sn = cross(ray.origin, d);
  const double den_l = cross(fl.edge, d), den_r = cross(fr.edge, d);
  const bool away_l = sn * den_l < 0.0, away_r = sn * den_r < 0.0;
  if (away_r & !away_l) {
    on = Side::left;
    s = hit_facet_with(ray.origin, fl, sn, den_l);
  } else if (away_l & !away_r) {
    on = Side::right;
    s = hit_facet_with(ray.origin, fr, sn, den_r);
  } else {
    const FacetHit hl = hit_facet_from_rim_line(ray.origin, d, fl);
    const FacetHit hr = hit_facet_from_rim_line(ray.origin, d, fr);
    if (hl.s >= 0.0 && (hr.s < 0.0 || hl.t_num / hl.t_den <= hr.t_num / hr.t_den))
      on = Side::left, s = hl.s;
    else
      on = Side::right, s = hr.s;
  }
  return s >= 0.0;
}

// sim::trace's step inside the groove (detail::bounce after its reflection), the same operations
// in the same order: a path in medium 1 leaving facet `on` at s along d meets the other facet at
// s_next (true), or leaves through the opening (false).
inline bool step_to_other_facet(const Groove& g, Side on, double s, const Vec2& d, double& s_next) {
  const Facet& f = g[on];
  const Facet& o = g[other(on)];
  const double den = cross(o.edge, d);
  if (!(den * f.turn_to_other > 0.0)) return false;  // t <= 0: leaves through the opening
  const double c = cross(f.edge, d);
  if (c * den < 0.0 || s * std::abs(c) > o.length * std::abs(den)) return false;  // passes the other facet
  s_next = s * (c / den);
  return true;
}

// Throws std::invalid_argument naming the field and its range (eta, min_weight, max_interactions).
void check_dielectric_options(const DielectricOptions& opt);

// The ray's direction against the medium its light comes from: "ray.dir.y = ... is out of range".
void check_light_direction(const Vec2& dir, Medium from);

}  // namespace vgroove::sim::detail
