// vgroove sim: one hit of a path on a dielectric interface, shared by the dielectric tracers
// (sim/dielectric_groove.h, sim/dielectric_microsurface.h): the reflected share F at the local
// angle and the refracted direction, and the checks of the tracers' options.
#pragma once

#include "vgroove/optics/fresnel.h"
#include "vgroove/optics/snell.h"
#include "vgroove/sim/dielectric_groove.h"

#include <cmath>

namespace vgroove::sim::detail {

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

// Throws std::invalid_argument naming the field and its range (eta, min_weight, max_interactions).
void check_dielectric_options(const DielectricOptions& opt);

// The ray's direction against the medium its light comes from: "ray.dir.y = ... is out of range".
void check_light_direction(const Vec2& dir, Medium from);

}  // namespace vgroove::sim::detail
