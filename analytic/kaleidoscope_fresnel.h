// vgroove analytic: the energy the kaleidoscopic model gives a path of n reflections, with Fresnel.
// Lee et al. 2018, "Practical Multiple Scattering for Rough Surfaces", Eq. (11) (symmetric) and
// the R term of Eq. (23) (nonsymmetric): a path of n reflections keeps prod_{j=1..n} F(cos theta_j),
// the local angle at bounce j in closed form (by unfolding the groove, Sec. 4.1):
//   symmetric, left facet first:     cos theta_j = |sin((2j - 1) theta_v/2 - theta_i)|,
//   nonsymmetric, left facet first:  cos theta_j = |cos(theta_i - theta_l - (j - 1) theta_v)|,
// the right facet first by the mirror image. The local angles depend on the bounce index only, not
// on where the ray enters. Conventions as in analytic/kaleidoscope.h.
// Tests: tests/validation/fresnel_groove_test.cpp (FresnelGroove.TracedLocalAnglesAreTheClosedFormSymmetric,
// FresnelGroove.TracedLocalAnglesAreTheClosedFormNonsymmetric, FresnelGroove.SymmetricAndNonsymmetricFormsAgree,
// FresnelGrooveSymmetric.EveryRayKeepsTheModelsEnergy, FresnelGrooveNonsymmetric.EveryRayKeepsTheModelsEnergy).
// Derivation: docs/derivations/kaleidoscope.md.
#pragma once

#include "vgroove/analytic/kaleidoscope.h"

namespace vgroove::analytic {

// cos theta_j of bounce j (1-based) in a symmetric groove of aperture theta_v, for light hitting
// `first` first.
double local_cos_theta(double theta_i, double theta_v, int j, FacetSide first);

// The same in a nonsymmetric groove (theta_l <= 0 <= theta_r, aperture pi + theta_l - theta_r > 0).
double local_cos_theta_nonsymmetric(double theta_i, double theta_l, double theta_r, int j, FacetSide first);

// Eq. (11): prod_{j=1..n} F(cos theta_j) for a path of n reflections; 1 for n = 0. F is any
// callable double(double cos_theta) (optics/fresnel.h's functions, sim/effects.h's functors).
template <class Reflectance>
double fresnel_energy(double theta_i, double theta_v, int n, FacetSide first, const Reflectance& F) {
  double e = 1.0;
  for (int j = 1; j <= n; ++j) e *= F(local_cos_theta(theta_i, theta_v, j, first));
  return e;
}

// Eq. (23)'s R without G: prod_{j} F over the n bounces in a nonsymmetric groove.
template <class Reflectance>
double fresnel_energy_nonsymmetric(double theta_i, double theta_l, double theta_r, int n, FacetSide first,
                                   const Reflectance& F) {
  double e = 1.0;
  for (int j = 1; j <= n; ++j) e *= F(local_cos_theta_nonsymmetric(theta_i, theta_l, theta_r, j, first));
  return e;
}

}  // namespace vgroove::analytic
