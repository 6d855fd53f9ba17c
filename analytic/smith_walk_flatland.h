// vgroove analytic: the Smith multiple-scattering random walk of Heitz, Hanika, d'Eon and
// Dachsbacher ("Multiple-Scattering Microfacet BSDFs with the Smith Model", ACM TOG 35(4), 2016),
// written for flatland, for a conductor with F = 1. A model, not a simulation: a pure function of
// the uniform numbers its caller supplies (no generator in analytic/).
//
// The microsurface of the walk is Smith's: heights h with any distribution function C1 and slopes
// independent of the heights, the flatland slope law of the NDF (analytic/ndf.h). The walk's
// state is the ray's direction and C1(h) at its last intersection; it never needs h itself, so it
// keeps lc = log C1(h) <= 0 (lc = 0: above the whole surface).
//
// Free paths (Heitz et al. 2016, Sec. 4; derived again here in flatland). A ray at height h going
// up along a direction with Smith's Lambda escapes without meeting the surface with probability
// G1(h) = C1(h)^Lambda (Smith's shadowing at a height; its 2D form has the same Lambda, since
// Smith's Lambda only depends on the slopes along the ray's azimuth, analytic/ndf.h), and
// otherwise meets it below the height where C1 = C1(h) / xi^(1/Lambda) for xi uniform: with
// xi in (0, 1),
//   up:    leaves when log xi < Lambda lc, else lc' = lc - log(xi) / Lambda;
//   down:  always meets the surface, lc' = lc + log(xi) / (1 + Lambda_rev),
// Lambda_rev of the reversed (upward) direction. (A downward direction's own Lambda is
// -1 - Lambda_rev; both branches are C1(h') = C1(h) xi^(-1/Lambda).) A level ray stays at its
// height and does not leave (Lambda infinite).
//
// Phase function. At an intersection the facet normal is drawn from the distribution of normals
// visible from where the ray comes from, v = -d (Heitz et al. 2016, Sec. 5; Heitz and d'Eon 2014):
//   D_v(m) = (cos(theta_v - m))+ D2(m) / A(v),   A(v) = int (cos(theta_v - m))+ D2(m) dm,
// for any v, up or down; the ray leaves the facet mirrored, theta' = 2 m - theta_v. In slope
// space (s = tan m, D2 dm = P(s) ds / cos m, cos(theta_v - m) = cos m (a + b s) with a = cos
// theta_v, b = sin theta_v) the visible slopes have the density (a + b s)+ P(s) / A. For b > 0
// the support is s > s0 = -a / b and the upper tail U(s) = int_s^inf (a + b t) P(t) dt is:
//   Beckmann (P = e^{-s^2/alpha^2} / (alpha sqrt pi), x = s / alpha):
//     U = (a / 2) erfc(x) + b alpha e^{-x^2} / (2 sqrt pi);
//   GGX (P = (1 + s^2/alpha^2)^{-3/2} / (2 alpha), x = s / alpha = tan phi):
//     U = (a / 2) (1 - sin phi) + (b alpha / 2) cos phi,
// and A = U(s0). For an upward v this is A = cos theta_v (1 + Lambda(v)) (the projected-area
// constraint, Heitz 2014 Eq. 5); for a downward one A = |cos theta_v| Lambda(-v). Sampling inverts
// U(s) = (1 - u) A: GGX in closed form,
//   s = alpha tan(psi - pi/2 + 2 asin(sqrt(u w / 2))),  psi = atan2(b alpha, a),
//   R = sqrt(a^2 + b^2 alpha^2), w = (R + a) / R,
// (with a sin phi - b alpha cos phi = R sin(phi - psi), and phi running from psi - pi/2 at s0 to
// pi/2); Beckmann by safeguarded Newton iteration on U. b < 0 is the mirror image (s -> -s).
//
// The walk: the ray enters travelling along -i from above the surface (lc = 0), and alternates a
// free path and a reflection until a free path leaves; the number of reflections is the bounce
// count k, the last direction the exit direction o. The single-scattering part (k = 1) is the
// flatland microfacet BRDF with the height-correlated masking-shadowing function (Heitz 2014,
// Eq. 21):
//   rho_1 cos(theta_o) = D2(h) cos(theta_i - h) / (2 cos theta_i (1 + Lambda(i) + Lambda(o))),
//   h = (theta_i + theta_o) / 2,
// (the first hit's C1 is xi^{1 / (1 + Lambda(i))}, and E[C1^Lambda(o)] = (1 + Lambda(i)) /
// (1 + Lambda(i) + Lambda(o))); the tests check the walk against it.
//
// Conventions (analytic/ndf.h): angles from the macrosurface normal, counter-clockwise positive,
// the direction at theta is (-sin theta, cos theta); travel directions may point anywhere, angles
// in (-pi, pi]. Beckmann and GGX only (Phong has no closed-form Lambda).
#pragma once

#include "vgroove/analytic/ndf.h"

#include <cmath>
#include <numbers>

namespace vgroove::analytic {

// A(v) = int (cos(theta_view - m))+ D2(m) dm, the projected length of the facets facing the
// direction at theta_view (any angle), per unit macrosurface length.
double visible_projected_length(NdfKind ndf, double alpha, double theta_view);

// The distribution of visible normals D_v(m) over m in (-pi/2, pi/2), and a sample of it from
// u in (0, 1) (monotone in u). theta_view must see some facet (A(v) > 0).
double visible_normal_pdf(NdfKind ndf, double alpha, double theta_view, double m);
double sample_visible_normal(NdfKind ndf, double alpha, double theta_view, double u);

// One free path: from lc = log C1(h) <= 0 along the direction at theta_travel, with xi in (0, 1):
// the new lc, or +infinity when the ray leaves the surface.
double walk_free_path(NdfKind ndf, double alpha, double lc, double theta_travel, double xi);

// theta folded into (-pi, pi].
inline double wrap_angle(double theta) {
  const double r = std::remainder(theta, 2.0 * std::numbers::pi);
  return r == -std::numbers::pi ? std::numbers::pi : r;
}

struct FlatlandWalk {
  int k = 0;             // reflections
  double theta_o = 0.0;  // exit direction, in (-pi/2, pi/2], when left
  bool left = false;     // false: still inside after max_k reflections
};

// The walk from theta_i in (-pi/2, pi/2); uniform() returns numbers in (0, 1), one per free path
// and one per reflection, in that order.
template <class Uniform>
FlatlandWalk smith_walk_flatland(NdfKind ndf, double alpha, double theta_i, Uniform&& uniform, int max_k = 100000) {
  FlatlandWalk w;
  double theta = wrap_angle(theta_i + std::numbers::pi);  // travelling along -i
  double lc = 0.0;
  for (;;) {
    const double next = walk_free_path(ndf, alpha, lc, theta, uniform());
    if (std::isinf(next)) {
      w.theta_o = theta;
      w.left = true;
      return w;
    }
    if (w.k == max_k) return w;
    lc = next;
    ++w.k;
    const double theta_v = wrap_angle(theta + std::numbers::pi);  // towards where the ray came from
    const double m = sample_visible_normal(ndf, alpha, theta_v, uniform());
    theta = wrap_angle(2.0 * m - theta_v);
  }
}

}  // namespace vgroove::analytic
