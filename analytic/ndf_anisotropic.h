// vgroove analytic: roughness with two axes (anisotropic Beckmann and GGX) for the V-groove
// models, Lee et al. 2018 ("Practical Multiple Scattering for Rough Surfaces"), Fig. 7; the
// elliptical NDFs of Heitz 2014 ("Understanding the Masking-Shadowing Function in Microfacet-
// Based BRDFs", JCGT 3(2)), Sec. 5.3. Along an azimuth phi from the alpha_x axis,
//   D(theta, phi) = alpha(phi)^2 / (alpha_x alpha_y) D_iso(theta; alpha(phi)),
//   1/alpha(phi)^2 = cos^2(phi) / alpha_x^2 + sin^2(phi) / alpha_y^2,
// so azimuths have the density alpha(phi)^2 / (2 pi alpha_x alpha_y) and, given phi, the tilt and
// the partner law are the isotropic ones at alpha(phi). Phong stays isotropic.
// Tests: tests/analytic/lobe_nonsymmetric_test.cpp (NonsymmetricLobe.AnisotropicConsistency),
// tests/sim/microsurface_nonsymmetric_test.cpp (NonsymmetricMicrosurface.AlphaAlongTheAxes,
// NonsymmetricPopulation.AnisotropicSlopesAndPartners).
// Derivation: docs/derivations/ndf.md.
#pragma once

#include "vgroove/analytic/ndf.h"

namespace vgroove::analytic {

struct Roughness {
  NdfKind ndf = NdfKind::beckmann;
  double alpha_x = 0.5;
  double alpha_y = 0.5;
  bool isotropic() const { return alpha_x == alpha_y; }
};

inline Roughness isotropic_roughness(NdfKind ndf, double alpha) { return Roughness{ndf, alpha, alpha}; }

// alpha(phi): 1/alpha^2 = cos^2(phi)/alpha_x^2 + sin^2(phi)/alpha_y^2 (alpha_x when isotropic).
double alpha_along(const Roughness& r, double phi);

// D(theta_m, phi_m) of the facet normal at tilt theta_m and azimuth phi_m (from the alpha_x axis).
double D_anisotropic(const Roughness& r, double theta_m, double phi_m);

}  // namespace vgroove::analytic
