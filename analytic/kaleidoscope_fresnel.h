// vgroove analytic: the energy the kaleidoscopic model gives a path of n reflections, with Fresnel.
//
// Lee et al. 2018, "Practical Multiple Scattering for Rough Surfaces", Eq. (11) (symmetric) and
// the R term of Eq. (23) (nonsymmetric): a path of n reflections keeps prod_{j=1..n} F(cos theta_j),
// theta_j the local angle of incidence at bounce j. Conventions as in analytic/kaleidoscope.h.
//
// The local angle at bounce j, in closed form. Unfold the groove (Sec. 4.1): instead of
// reflecting the ray at a facet, reflect the groove across it; the ray then runs straight along
// its incident direction, at angle theta_i + pi from n, through a fan of facet images. Light
// hitting the left facet first meets, in turn, the left facet's line (edge at angle theta_v/2
// from n) and the images of the two facet lines, each turned theta_v further:
//   line of bounce j (j = 1, 2, ...):  phi_j = theta_v/2 + (j - 1) theta_v.
// Reflections preserve angles, so the angle between the real ray and the real facet at bounce j
// equals the angle between the straight ray and line j. For a direction at angle alpha and a line
// at angle phi the cosine to the line's normal is |sin(alpha - phi)|, so
//   cos theta_j = |sin((2j - 1) theta_v/2 - theta_i)|,
// i.e. theta_j = |theta_i + pi/2 - theta_v/2 - (j - 1) theta_v| folded into [0, pi/2].
// The same follows without unfolding from Eq. (5): before bounce j the ray has made j - 1
// reflections and travels at alpha = (-1)^(j-1) (theta_i + pi - (j - 1) theta_v); bounce j is on
// the left facet (normal at theta_v/2 - pi/2) for odd j and on the right one (normal at
// pi/2 - theta_v/2) for even j, and |cos(alpha - normal angle)| reduces to the same expression.
// For a bounce that happens the ray crosses line j, so the sine lies in (0, 1]; the absolute value
// only absorbs rounding. The right facet first is the mirror image: theta_i -> -theta_i.
//
// Nonsymmetric grooves (Sec. 4.2, Fig. 5): the left facet runs along theta_l + pi/2 and its images
// lie at theta_l + pi/2 + (j - 1) theta_v with theta_v = pi + theta_l - theta_r, so
//   cos theta_j = |cos(theta_i - theta_l - (j - 1) theta_v)|   (left facet first);
// mirrored (x -> -x turns the groove (theta_l, theta_r) into (-theta_r, -theta_l) and theta_i into
// -theta_i), cos theta_j = |cos(theta_i - theta_r + (j - 1) theta_v)| for the right facet first.
// With theta_l = theta_v/2 - pi/2 both reduce to the symmetric form.
//
// The local angles depend on the bounce index only, not on where the ray enters: every ray of a
// (first facet, n) bin keeps the same energy.
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
