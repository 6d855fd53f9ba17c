// vgroove sim: the tilt of a nonsymmetric groove's second facet (the paper's theta_r), drawn so
// that the surface keeps the NDF's distribution of facet normals.
//
// Lee, Jarabo, Jeon, Gutierrez, Kim. "Practical Multiple Scattering for Rough Surfaces". ACM TOG
// 37(6), 2018, Sec. 5.2, Eq. (18)-(20). Derived here from the slope laws, independently of
// analytic/partner_distribution.h (sim/ and analytic/ never include each other; tests compare).
//
// Why this law. A groove whose rims lie on the macrosurface and whose facets have the tilts a and
// b (normals at a and b from n) and depth h spans the macro widths h / tan a and h / tan b. Let the
// first facet's tilt follow the law q(a) of a facet under a uniform point of the macrosurface
// (sim/microsurface3d.h: q = 2 pi D cos sin in 3D; sim/slope_sampling.h: 2 D2 cos folded onto
// a > 0 in flatland) and give the second one the tilt b ~ r independently. The second facets then
// cover, per first facet of width w, the width w tan a / tan b, so in projected area their tilts
// follow r(b) / tan(b) (times E[tan a]). They follow q as well exactly when
//   r(b) = q(b) tan(b) / E_q[tan],
// the tilt law weighted by tan: Eq. (20) of the paper, D(b) sin^2(b) / int D sin^2, read with
// q = 2 pi D cos sin (3D), and D2(b) sin(b) / int D2 sin in flatland.
//
// In slopes x = tan b (the slope densities of sim/slope_sampling.h and sim/microsurface3d.h:
// P22 the isotropic 2D slope density, P its 1D marginal along a cut), q(b) db is P22(x) 2 pi x dx
// in 3D and 2 P(x) dx in flatland, so r is
//   3D:       x^2 P22(x) dx / norm:
//     Beckmann: x^2 exp(-x^2/alpha^2): y = x^2/alpha^2 is Gamma(3/2)-distributed;
//               CDF = P(3/2, y) = erf(sqrt y) - 2 sqrt(y/pi) exp(-y).
//     GGX:      x^2 / (alpha^2 + x^2)^2: with psi = atan(x/alpha), CDF = (2 psi - sin 2 psi) / pi.
//     Phong:    cos^p sin^2 db (D = (p+2)/(2 pi) cos^p, p = 2/alpha^2 - 2): w = sin^2 b is
//               Beta(3/2, (p+1)/2)-distributed; CDF = I_{sin^2 b}(3/2, (p+1)/2).
//   Flatland: x P(x) dx / norm:
//     Beckmann: x exp(-x^2/alpha^2):          CDF = 1 - exp(-x^2/alpha^2).
//     GGX:      x (1 + x^2/alpha^2)^(-3/2):    CDF = 1 - (1 + x^2/alpha^2)^(-1/2).
//     Phong:    cos^p sin db:                  CDF = 1 - cos^(p+1) b.
// Phong needs p > -1 (alpha < sqrt 2) for r to be normalizable: rougher Phong surfaces have no
// such partner law (asserted).
//
// Sampling. Flatland: the inverse CDF in closed form (u -> theta_r, monotone). 3D: Beckmann from
// Gamma(3/2) = Exp(1) + Z^2/2 (three uniforms, no rejection); GGX by Newton on Kepler's equation
// beta - sin beta = pi u (beta = 2 psi, one uniform); Phong as atan2(sqrt X, sqrt Y) with X ~
// Gamma(3/2), Y ~ Gamma((p+1)/2) (Marsaglia and Tsang's method; the number of uniforms it takes
// varies, so the 3D samplers draw from an Rng).
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
