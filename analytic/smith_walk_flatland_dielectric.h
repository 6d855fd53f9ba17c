// vgroove analytic: the Smith multiple-scattering random walk of Heitz, Hanika, d'Eon, Dachsbacher
// (ACM TOG 35(4), 2016; its dielectric microsurface) in flatland: medium 1 above, medium 2 below,
// eta = n2 / n1, light from either side, Beckmann and GGX. The conductor walk
// (analytic/smith_walk_flatland.h) in the frame of the medium the ray is in: medium 2 sees the
// microsurface flipped (heights -h: log C1 -> log(1 - C1)); at each intersection the ray reflects
// with probability F (dielectric Fresnel at the local angle, 1 under TIR), else refracts (Snell).
// A pure function of its caller's uniform numbers. Holds: F = 1 is the conductor walk bit for bit;
// eta = 1 passes straight through; its k = 1 energies are their quadratures. Against traced random
// profiles (sim/dielectric_polyline.h) a model whose misses are measured.
// Tests: tests/analytic/smith_walk_flatland_dielectric_test.cpp (SmithWalkDielectric.ConductorLimitIsTheConductorWalk,
// SmithWalkDielectric.EtaOnePassesStraightThrough,
// SmithWalkDielectric.SingleScatteringIsFresnelWithTheHeightCorrelatedEscape,
// SmithWalkDielectric.EveryWalkLeavesAndHardCasesStayFinite); tests/validation/smith_walk_dielectric_profiles_test.cpp
// (SmithWalkDielectricProfiles.FirstInteractionAtNormalIncidenceIsExactOnBothSides,
// SmithWalkDielectricProfilesLong.FullGrid). Derivation: docs/derivations/smith_walk_dielectric.md.
#pragma once

#include "vgroove/analytic/smith_walk_flatland.h"
#include "vgroove/optics/fresnel.h"
#include "vgroove/optics/snell.h"

#include <cmath>
#include <cstdint>
#include <numbers>

namespace vgroove::analytic {

// The two media: medium 1 above the interface, medium 2 below (sim::Medium's order).
enum class WalkMedium : unsigned char { above = 0, below = 1 };

// log(1 - e^lc) for lc <= 0, without cancellation: log C1 of the flipped microsurface at the point
// where the upright one has log C1 = lc (-infinity at lc = 0, 0 at lc = -infinity).
double log1m_exp(double lc);

// The reflectance of one hit: the unpolarized dielectric Fresnel reflectance (optics/fresnel.h) at
// cos_i for the relative index eta_rel (far over near), when Snell's law has a transmitted ray.
struct DielectricFresnelLaw {
  double operator()(double cos_i, double eta_rel) const { return optics::fresnel_dielectric(cos_i, eta_rel); }
};

struct DielectricWalkOptions {
  double eta = 1.5;              // n2 / n1, > 0
  bool conductor_limit = false;  // F = 1 at every hit: the conductor walk
  int max_k = 100000;            // interactions before the walk gives up (left = false)
};

struct FlatlandDielectricWalk {
  int k = 0;  // interactions (reflections and refractions)
  // Exit angle from the normal of the exit side, counter-clockwise positive, in (-pi/2, pi/2]:
  // sim::exit_angle's convention (above: angle_from_normal of the direction; below: phi with the
  // direction (sin phi, -cos phi)).
  double theta_o = 0.0;
  std::uint64_t path = 0;               // bit j set: interaction j refracted (the first 64)
  WalkMedium side = WalkMedium::above;  // the medium it left into
  bool left = false;                    // false: still inside after max_k interactions
};

// The walk of light arriving from `from` at theta_i in (-pi/2, pi/2), measured from the normal of
// that side as exit angles are (light from above travels along (sin theta_i, -cos theta_i), light
// from below along (-sin theta_i, cos theta_i)). uniform() returns numbers in (0, 1): one per free
// path, one per intersection (the facet normal), and one per intersection with F < 1 (the choice),
// in that order. law(cos_i, eta_rel) gives F where Snell's law transmits (DielectricFresnelLaw).
template <class Uniform, class Law = DielectricFresnelLaw>
FlatlandDielectricWalk smith_walk_flatland_dielectric(NdfKind ndf, double alpha, double theta_i, WalkMedium from,
                                                      const DielectricWalkOptions& opt, Uniform&& uniform,
                                                      const Law& law = Law{}) {
  constexpr double pi = std::numbers::pi;
  FlatlandDielectricWalk w;
  WalkMedium medium = from;
  // The frame of the medium the ray travels in: medium 1's is the world's, medium 2's the world's
  // mirrored in the mean plane (y -> -y), where the flipped microsurface lies above and angles
  // change sign. The ray enters travelling along -i.
  double theta = wrap_angle((from == WalkMedium::above ? theta_i : -theta_i) + pi);
  double lc = 0.0;
  for (;;) {
    const double next = walk_free_path(ndf, alpha, lc, theta, uniform());
    if (std::isinf(next)) {
      w.theta_o = medium == WalkMedium::above ? theta : -theta;
      w.side = medium;
      w.left = true;
      return w;
    }
    if (w.k == opt.max_k) return w;
    lc = next;
    const int j = w.k++;
    const double theta_v = wrap_angle(theta + pi);  // towards where the ray came from
    const double m = sample_visible_normal(ndf, alpha, theta_v, uniform());
    if (opt.conductor_limit) {
      theta = wrap_angle(2.0 * m - theta_v);
      continue;
    }
    // The local angle from the facet normal (the sampler keeps cos > 0 but for rounding).
    const double phi_i = wrap_angle(theta_v - m);
    const double eta_rel = medium == WalkMedium::above ? opt.eta : 1.0 / opt.eta;
    const double cos_i = std::cos(phi_i);
    const double cos_t = optics::snell_cos_transmitted(cos_i, eta_rel);
    const double F = cos_t < 0.0 ? 1.0 : law(cos_i, eta_rel);
    if (F >= 1.0 || uniform() < F) {
      theta = wrap_angle(2.0 * m - theta_v);
      continue;
    }
    // Refraction: the travel direction turns from -m by phi_t (the side of -i's phi_i), at angle
    // m + pi + phi_t in this frame, which is -m - phi_t in the other medium's.
    const double phi_t = eta_rel == 1.0 ? phi_i : std::atan2(std::sin(phi_i) / eta_rel, cos_t);
    theta = wrap_angle(-m - phi_t);
    medium = medium == WalkMedium::above ? WalkMedium::below : WalkMedium::above;
    lc = log1m_exp(lc);
    if (j < 64) w.path |= std::uint64_t{1} << j;
  }
}

}  // namespace vgroove::analytic
