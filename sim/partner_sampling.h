// vgroove sim: the tilt of a nonsymmetric groove's second facet (the paper's theta_r), drawn so
// that the surface keeps the NDF's distribution of facet normals. Lee et al. 2018 ("Practical
// Multiple Scattering for Rough Surfaces", ACM TOG 37(6)), Sec. 5.2, Eq. (18)-(20), derived here
// from the slope laws independently of analytic/partner_distribution.h (tests compare):
//   r(b) = q(b) tan(b) / E_q[tan],   q the tilt law of a facet under a uniform macro point.
// Flatland by closed-form inverse CDFs; 3D Beckmann from Gamma(3/2), GGX by Newton on Kepler's
// equation, Phong by two Gamma variates (Marsaglia-Tsang). Phong needs alpha < sqrt 2 (asserted).
// Tests: tests/sim/partner_sampling_test.cpp (PartnerSampling.DensitiesIntegrateToTheirDistributionFunctions,
// PartnerSampling.FlatlandInverseInvertsTheDistributionFunction, PartnerSampling.DrawsFollowTheLawByChiSquare,
// IndependentPairs.KeepTheNdfInProjectedArea, IndependentPairs.NaiveIndependentTiltsAreRejected).
// Derivation: docs/derivations/nonsymmetric.md.
#pragma once

#include "vgroove/common/ndf_kind.h"
#include "vgroove/sim/rng.h"

namespace vgroove::sim {

// Whether the partner law exists: Beckmann and GGX always, Phong for alpha < sqrt(2).
bool theta_r_law_exists(NdfKind kind, double alpha);

// 3D: density of theta_r in [0, pi/2), its distribution function, and a draw.
double theta_r_pdf_3d(NdfKind kind, double alpha, double theta_r);
double theta_r_cdf_3d(NdfKind kind, double alpha, double theta_r);
double sample_theta_r_3d(NdfKind kind, double alpha, Rng& rng);

// Flatland: density, distribution function and its inverse (u in (0, 1) -> [0, pi/2), monotone).
double theta_r_pdf(NdfKind kind, double alpha, double theta_r);
double theta_r_cdf(NdfKind kind, double alpha, double theta_r);
double sample_theta_r(NdfKind kind, double alpha, double u);

// A Gamma(shape, 1) variate (Marsaglia and Tsang 2000; shape < 1 through Gamma(shape + 1) U^(1/shape)).
double sample_gamma(double shape, Rng& rng);

}  // namespace vgroove::sim
