// vgroove analytic: the Smith multiple-scattering random walk of Heitz, Hanika, d'Eon, Dachsbacher
// ("Multiple-Scattering Microfacet BSDFs with the Smith Model", ACM TOG 35(4), 2016, Sec. 4-5)
// in flatland, for a conductor with F = 1: free paths from C1(h)^Lambda, facet normals from the
// visible slopes (GGX in closed form, Beckmann by safeguarded Newton). A model, not a simulation:
// a pure function of the uniform numbers its caller supplies. Beckmann and GGX only.
// Holds: the visible projected length is the projected-area constraint (Heitz 2014, Eq. 5); the
// visible-slope sampler inverts its distribution; the walk's k = 1 part is the flatland microfacet
// BRDF with the height-correlated G (Heitz 2014, Eq. 21) within statistics; hard cases finite.
// Tests: tests/analytic/smith_walk_flatland_test.cpp
// (SmithWalkFlatland.VisibleProjectedLengthIsTheProjectedAreaConstraint,
// SmithWalkFlatland.VisibleNormalSamplerInvertsItsDistribution, SmithWalkFlatland.FreePathsByHand,
// SmithWalkFlatland.SingleScatteringIsTheHeightCorrelatedMicrofacetBrdf,
// SmithWalkFlatland.HardCasesStayFinite).
// Derivation: docs/derivations/smith_walk.md.
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
