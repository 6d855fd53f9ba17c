// vgroove analytic: P(theta_r), the law of a nonsymmetric V-groove's second facet, Lee et al. 2018
// ("Practical Multiple Scattering for Rough Surfaces", ACM TOG 37(6)), Sec. 5.2, Eq. (18)-(20)
// and App. C, in 3D and its flatland analogue, with the anisotropic partner law per azimuth:
//   P(b) = D(b) sin^2(b) / N,  N = int_0^{pi/2} D sin^2  (flatland: P2 = D2 sin / N2),
// N in closed form per NDF. App. C's printed constant is not 1/N (ERRATA E-NS1). Phong needs
// alpha < sqrt(2) (std::domain_error otherwise).
// Holds: P integrates to 1 and matches Eq. (20) pointwise; it is the tilt law weighted by tan;
// the closed-form N against quadrature.
// Tests: tests/analytic/partner_distribution_test.cpp (PartnerLaw.IntegratesToOneAndMatchesEq20Pointwise,
// PartnerLaw.NormalizationIsTheQuadratureOfEq20, PartnerLaw.IsTheTiltLawWeightedByTanTheta,
// PartnerLaw.AppendixCAsPrintedIsNotADensity, PartnerLaw.PhongNeedsAlphaBelowSqrt2).
// Derivation: docs/derivations/nonsymmetric.md.
#pragma once

#include "vgroove/analytic/ndf.h"

namespace vgroove::analytic {

// Whether the partner law exists (N finite): always for Beckmann and GGX, alpha < sqrt(2) for Phong.
bool partner_law_exists(NdfKind ndf, double alpha);

// 3D: N = int_0^{pi/2} D sin^2 (closed form) and Eq. (20), P(theta_r) = D(theta_r) sin^2 / N,
// zero outside [0, pi/2). Integrates to 1 over [0, pi/2).
double P_theta_r_normalization(NdfKind ndf, double alpha);
double P_theta_r(NdfKind ndf, double theta_r, double alpha);
// App. C as printed (E-NS1: not normalized).
double P_theta_r_printed(NdfKind ndf, double theta_r, double alpha);

// Flatland: N2 = int_0^{pi/2} D2 sin and P2(theta_r) = D2(theta_r) sin / N2 on [0, pi/2).
double P2_theta_r_normalization(NdfKind ndf, double alpha);
double P2_theta_r(NdfKind ndf, double theta_r, double alpha);

}  // namespace vgroove::analytic
