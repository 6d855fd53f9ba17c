// vgroove analytic: roughness with two axes (anisotropic Beckmann and GGX) for the V-groove
// models, Lee et al. 2018, Fig. 7 ("an anisotropic Beckmann NDF", alpha_x = 0.1, alpha_y varying).
//
// Lee, Jarabo, Jeon, Gutierrez, Kim. "Practical Multiple Scattering for Rough Surfaces".
// ACM TOG 37(6), 2018. The elliptical NDFs are those of Heitz 2014 ("Understanding the
// Masking-Shadowing Function in Microfacet-Based BRDFs", JCGT 3(2)), Sec. 5.3: the slope density
// P22(m) = P22_1(m_x / alpha_x, m_y / alpha_y) / (alpha_x alpha_y), P22_1 the unit-roughness law.
//
// Along one azimuth phi of the facet normal (measured from the alpha_x axis) the slope is
// tan(theta) (cos phi, sin phi) up to sign, so m_x^2 / alpha_x^2 + m_y^2 / alpha_y^2 =
// tan^2(theta) / alpha(phi)^2 with 1/alpha(phi)^2 = cos^2(phi) / alpha_x^2 + sin^2(phi) / alpha_y^2:
//   D(theta, phi) = alpha(phi)^2 / (alpha_x alpha_y) D_iso(theta; alpha(phi)),
// (Beckmann: exp(-tan^2 / alpha(phi)^2) / (pi alpha_x alpha_y cos^4); GGX: 1 / (pi alpha_x alpha_y
// cos^4 (1 + tan^2 / alpha(phi)^2)^2)), the isotropic NDF at the roughness along that azimuth. So:
//   - the facets' azimuths have the density (alpha(phi)^2 / (alpha_x alpha_y)) / (2 pi) (the
//     projected area the azimuth holds; it integrates to 1 since int d phi / (A cos^2 + B sin^2) =
//     2 pi / sqrt(A B));
//   - given phi, the tilt has the isotropic law at alpha(phi), and the partner law of a
//     nonsymmetric groove (analytic/partner_distribution.h, "P(theta_r | phi_v)") is the isotropic
//     P at alpha(phi).
// Phong has no elliptical form here: it stays isotropic (alpha_x == alpha_y).
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
