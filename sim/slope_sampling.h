// vgroove sim: facet normal angles of a flatland rough profile, drawn from its slope distribution.
//
// Derived here from the slopes, independently of analytic/ndf.h (sim/ and analytic/ never include
// each other; tests compare the two). Papers: Lee, Jarabo, Jeon, Gutierrez, Kim, "Practical
// Multiple Scattering for Rough Surfaces", ACM TOG 37(6) 2018 (Sec. 6 samples facets with the pdf
// |s.n| D(s)); Walter, Marschner, Li, Torrance, "Microfacet Models for Refraction through Rough
// Surfaces", EGSR 2007 (Beckmann, Phong, GGX; Phong exponent alpha_p = 2/alpha^2 - 2).
//
// The measure. A profile y = h(x) has slope s = h'(x) and facet normal angle theta_m = atan(s)
// (sim/geometry.h: the direction at theta is (-sin theta, cos theta), and the normal of slope s
// is (-s, 1)/|.|). Picking a point uniformly along the macrosurface (x) picks a facet with
// probability proportional to its projected length, so theta_m has the density
//   p(theta_m) = P(tan theta_m) / cos^2(theta_m)     over (-pi/2, pi/2),
// where P is the density of the slope along x. That is the flatland D2(theta_m) cos(theta_m).
//
// The slope laws: the slopes along one straight cut through the isotropic 3D surface, i.e. the
// marginal of its 2D slope density along one axis. Each is (alpha/sqrt(2)) times a standard law:
//   Beckmann: Gaussian:  P(s) = exp(-s^2/alpha^2) / (alpha sqrt(pi)).
//   GGX:      Student-t with nu = 2:  P(s) = (1 + s^2/alpha^2)^(-3/2) / (2 alpha).
//   Phong:    Student-t with nu = alpha_p + 2 = 2/alpha^2:
//             P(s) = Gamma((nu+1)/2) / (sqrt(pi) Gamma(nu/2)) (1 + s^2)^(-(nu+1)/2),
//             (the t density f(t) = Gamma((nu+1)/2) / (sqrt(nu pi) Gamma(nu/2)) (1 + t^2/nu)^(-(nu+1)/2)
//             with s = t / sqrt(nu) = alpha t / sqrt(2)).
// Lower tails T(theta) = P(theta_m <= theta) for theta <= 0 (the upper ones by symmetry):
//   Beckmann: T = erfc(|tan theta| / alpha) / 2.
//   GGX:      T = (1 - x / sqrt(1 + x^2)) / 2, x = |tan theta| / alpha.
//   Phong:    T = I_{cos^2 theta}(nu/2, 1/2) / 2 (the Student-t tail: the regularized incomplete
//             beta function at nu / (nu + t^2) = 1 / (1 + s^2) = cos^2 theta).
//   Student-T (Ribardiere et al. 2017, "STD: Student's t-Distribution of Slopes for Microfacet
//             Based BSDFs", CGF 36(2)), tail gamma > 1.5: its 3D slopes have the bivariate t law
//             (1 + |s|^2/k2)^-gamma, k2 = (gamma - 1) alpha^2, whose marginal along an axis is
//             proportional to (1 + s^2/k2)^(1/2 - gamma): a Student-t with nu = 2 gamma - 2 and
//             nu sigma^2 = k2, sigma = alpha/sqrt(2) (gamma = 2: GGX; gamma = 1 + 1/alpha^2: Phong),
//             P(s) = Gamma(gamma - 1/2) / (sqrt(pi k2) Gamma(gamma - 1)) (1 + s^2/k2)^(1/2 - gamma),
//             T = I_x(gamma - 1, 1/2) / 2, x = k2 / (k2 + tan^2 theta).
#pragma once

#include "vgroove/common/ndf_kind.h"

namespace vgroove::sim {

using vgroove::ndf_name;
using vgroove::NdfKind;

// Density of theta_m in (-pi/2, pi/2) in the projected-length measure; zero outside. alpha > 0.
double theta_m_pdf(NdfKind kind, double alpha, double theta_m);

// Its distribution function P(theta_m' <= theta_m); 0 below -pi/2, 1 above pi/2.
double theta_m_cdf(NdfKind kind, double alpha, double theta_m);

// The inverse of theta_m_cdf: u in [0, 1] to theta_m in [-pi/2, pi/2], monotone; u = 1/2 gives 0.
// GGX in closed form, the others by safeguarded Newton iteration on the log of the tail,
// to about 1e-15 rad (relative in the tails).
double sample_theta_m(NdfKind kind, double alpha, double u);

// Regularized incomplete beta function I_x(a, b), for x in [0, 1] given together with 1 - x
// (pass both when 1 - x is known more accurately than by subtraction). Continued fraction
// (Lentz); exposed for its tests.
double incomplete_beta(double a, double b, double x, double one_minus_x);

}  // namespace vgroove::sim
