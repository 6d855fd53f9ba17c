// vgroove analytic: the kaleidoscopic model of one symmetric V-groove between two dielectrics, lit
// from above (medium 1, eta = n2 / n1 > 0). In medium 1 the chain of reflections is Lee et al. 2018's
// kaleidoscope (Eq. 4-6), each hit's local angle Eq. (11)'s; at hit j the chain keeps F_j and
// refracts 1 - F_j. Per facet hit first, over its lit width as Eq. (6): reflected G_n prod F (Eq. 11),
// transmitted at hit j (sum_{n>=j} G_n) prod_{l<j} F_l (1 - F_j) along
// theta_t,j = (-1)^(j-1) (asin(cos beta_j / eta) - (pi - theta_v)/2), beta_j = (j - 1/2) theta_v - theta_i
// (KD-1..KD-3). `direct` (KD-4): the lobe leaves downward at once; in one groove with flat rims
// exactly the light that meets nothing more. Holds: R + T + shadow = 1 to rounding; eta = 1 passes
// all at hit 1 unbent; F = 1 is G_kaleidoscopic bit for bit; the exact split tracer to 1e-14.
// Tests: tests/analytic/kaleidoscope_dielectric_test.cpp (KaleidoscopeDielectric.*,
// KaleidoscopeDielectricTracer.MatchesSplitTracingToRounding, KaleidoscopeDielectricTracer.BrokenModelsFail).
// Derivation: docs/derivations/kaleidoscope_dielectric.md.
#pragma once

#include "vgroove/analytic/kaleidoscope.h"
#include "vgroove/analytic/kaleidoscope_fresnel.h"
#include "vgroove/optics/fresnel.h"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <vector>

namespace vgroove::analytic {

// The chain's travel direction before hit j (1-based) as an angle (direction_at convention): Eq. (5)
// with n = j - 1 reflections.
double chain_direction(double theta_i, double theta_v, int j, FacetSide first);

// The refraction at hit j of a chain entering `first` (KD-2, KD-3): the angle of incidence alpha
// (signed, from the facet's normal on the incident side; cos alpha = local_cos_theta) and the
// refracted direction's angle below, theta_t. Under total internal reflection (|sin alpha| >= eta)
// returns false, theta_t untouched.
bool refracted_angle(double theta_i, double theta_v, double eta, int j, FacetSide first, double& theta_t);

// One transmitted lobe: the rays refracted at hit j of their chain.
struct TransmittedLobe {
  int j = 0;
  double share = 0.0;      // of the rays aimed at the facet (G's normalization, f_a)
  double cos_theta = 0.0;  // local cos at hit j (Eq. 11's angle)
  double F = 1.0;          // Fresnel at hit j
  double theta_t = 0.0;    // direction: sim::exit_angle's angle below (0 when tir)
  bool tir = false;        // total internal reflection at hit j: share 0
  bool direct = false;     // leaves downward at once: cos theta_t > 0 (KD-4)
};

// One reflected lobe: chains of n hits (Eq. 6's zone) that keep prod F.
struct ReflectedLobe {
  int n = 0;
  double G = 0.0;      // Eq. (6)'s share of the facet's rays with n hits
  double share = 0.0;  // G prod_{l<=n} F_l (Eq. 11)
  double theta_o = 0.0;
};

struct DielectricFacetPrediction {
  bool lit = false;
  int k = 0;  // Eq. (4)
  double f_a = 0.0;
  double shadow = 0.0;  // Eq. (6): rays aimed at the facet that meet the other rim first
  ReflectedLobe fewer, more;
  std::vector<TransmittedLobe> transmitted;  // j = 1..k (k - 1 when the k-hit zone is empty)
  double reflected_total() const { return fewer.share + more.share; }
  double transmitted_total() const;
  // The lobes that do not leave downward at once (KD-4): what one groove cannot follow.
  double indirect_total() const;
};

// The model for the rays aimed at `first`, with any reflectance F(cos theta) at each hit (a
// callable double(double)): the unpolarized dielectric one by default, 1 for the conductor limit.
// Refraction directions are Snell's with eta whatever F is. eta > 0. The lobe vector has k entries:
// narrow grooves (k ~ pi / theta_v) make it long.
template <class Reflectance>
DielectricFacetPrediction kaleidoscope_dielectric_with(double theta_i, double theta_v, double eta, FacetSide first,
                                                       const Reflectance& F);

DielectricFacetPrediction kaleidoscope_dielectric(double theta_i, double theta_v, double eta, FacetSide first);

// ---- implementation of the template ----

template <class Reflectance>
DielectricFacetPrediction kaleidoscope_dielectric_with(double theta_i, double theta_v, double eta, FacetSide first,
                                                       const Reflectance& F) {
  DielectricFacetPrediction p;
  const FacetPrediction g = G_kaleidoscopic(theta_i, theta_v, first);
  p.lit = g.lit;
  if (!g.lit) return p;
  p.k = g.k, p.f_a = g.f_a, p.shadow = g.shadow;
  p.fewer.n = g.fewer.n, p.fewer.G = g.fewer.G, p.fewer.theta_o = g.fewer.theta_o;
  p.more.n = g.more.n, p.more.G = g.more.G, p.more.theta_o = g.more.theta_o;
  // Hits 1..k-1 are made by every entering ray, hit k by the k-zone only (KD-1).
  const int last = g.more.G > 0.0 ? g.k : g.k - 1;
  p.transmitted.reserve(static_cast<std::size_t>(std::max(last, 0)));
  double kept = 1.0;  // prod_{l<j} F_l
  for (int j = 1; j <= last; ++j) {
    TransmittedLobe t;
    t.j = j;
    t.cos_theta = local_cos_theta(theta_i, theta_v, j, first);  // Eq. (11)
    t.F = F(t.cos_theta);
    const double reaching = j <= g.k - 1 ? g.fewer.G + g.more.G : g.more.G;  // KD-1
    t.tir = !refracted_angle(theta_i, theta_v, eta, j, first, t.theta_t);
    t.share = t.tir ? 0.0 : reaching * kept * (1.0 - t.F);  // KD-2
    t.direct = !t.tir && std::cos(t.theta_t) > 0.0;         // KD-4
    p.transmitted.push_back(t);
    kept *= t.F;
    if (j == g.k - 1) p.fewer.share = g.fewer.G * kept;  // Eq. (11), n = k - 1
    if (j == g.k) p.more.share = g.more.G * kept;        // Eq. (11), n = k
  }
  if (g.k - 1 == 0) p.fewer.share = g.fewer.G;  // no hit (only at the apex boundary; G is 0 there)
  if (last < g.k) p.more.share = 0.0;
  return p;
}

}  // namespace vgroove::analytic
