// vgroove sim: effects applied along a traced path, as observers of sim::trace.
//
// Lee et al. 2018, "Practical Multiple Scattering for Rough Surfaces", Eq. (11): a path of k
// reflections keeps the product of the Fresnel reflectances at its bounces' local angles,
//   dPhi_o = prod_{j=1..k} F(cos theta_j) dPhi_i,
// where theta_j is the angle between the ray arriving at bounce j and the facet's normal there.
// The tracer calls obs.on_bounce(side, dir_in, facet) once per reflection, before reflecting, so
// cos theta_j = |dir_in . facet.normal|.
//
// What an effect costs is chosen at compile time (the design's "an effect the scene does not ask
// for costs nothing"): sim::trace is a template on its observer, NoBounceObserver compiles away,
// and FresnelEnergyObserver<UnitReflectance> does too (its on_bounce is empty by construction,
// not by the optimizer's grace). Select the observer type once per run, never per bounce.
//
// Header-only; the reflectance functors call optics/, so a target using them links vgroove::optics.
#pragma once

#include "vgroove/optics/fresnel.h"
#include "vgroove/sim/tracer.h"

#include <cmath>
#include <type_traits>

namespace vgroove::sim {

// Reflectance functors: double operator()(double cos_theta_i) const, cos_theta_i in [0, 1].

// F = 1: perfect mirrors (the paper's Table 1 and white furnace tests).
struct UnitReflectance {
  double operator()(double /*cos_theta_i*/) const { return 1.0; }
};

// Conductor of complex relative index eta + i kappa.
struct ConductorReflectance {
  double eta, kappa;
  double operator()(double cos_theta_i) const { return optics::fresnel_conductor(cos_theta_i, eta, kappa); }
};

// Dielectric of real relative index eta (reflection only: the refracted part is lost).
struct DielectricReflectance {
  double eta;
  double operator()(double cos_theta_i) const { return optics::fresnel_dielectric(cos_theta_i, eta); }
};

// Schlick's approximation with normal reflectance F0.
struct SchlickReflectance {
  double F0;
  double operator()(double cos_theta_i) const { return optics::fresnel_schlick(cos_theta_i, F0); }
};

// Multiplies `throughput` by the reflectance at each bounce's local angle (Eq. 11). Start a ray
// with throughput 1 (reset()), pass the observer to sim::trace by reference, read it afterwards:
//   FresnelEnergyObserver obs{ConductorReflectance{0.2, 3.0}};
//   const TraceResult r = trace(g, ray, opt, obs);   // obs.throughput: the energy the ray kept
// A ray that does not escape keeps the product over the reflections it made.
template <class Reflectance>
struct FresnelEnergyObserver {
  Reflectance reflectance;
  double throughput = 1.0;

  void reset() { throughput = 1.0; }
  void on_bounce(Side, const Vec2& dir_in, const Facet& f) {
    // F = 1 needs neither the cosine nor the product: nothing at all is done per bounce.
    if constexpr (!std::is_same_v<Reflectance, UnitReflectance>) {
      throughput *= reflectance(std::abs(dir_in.dot(f.normal)));
    }
  }
};
template <class Reflectance>
FresnelEnergyObserver(Reflectance) -> FresnelEnergyObserver<Reflectance>;

}  // namespace vgroove::sim
