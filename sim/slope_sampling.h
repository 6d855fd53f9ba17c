// vgroove sim: facet normal angles of a flatland rough profile, drawn from its slope distribution:
// theta_m = atan(s) with the density p(theta_m) = P(tan theta_m) / cos^2(theta_m) = D2 cos, P the
// marginal of the isotropic 3D slope law along an axis, each (alpha / sqrt 2) times a standard law:
// Beckmann Gaussian, GGX Student-t with nu = 2, Phong Student-t with nu = 2 / alpha^2, Student-T
// (Ribardiere et al. 2017) Student-t with nu = 2 gamma - 2; tails by erfc, closed forms and the
// regularized incomplete beta function. Derived from the slopes independently of analytic/ndf.h
// (tests compare). Lee et al. 2018, Sec. 6; Walter et al. 2007 (Phong exponent 2/alpha^2 - 2).
// Tests: tests/sim/microsurface_test.cpp (SlopeSampling.PdfIsNormalized,
// SlopeSampling.CdfIsTheIntegralOfThePdf, SlopeSampling.SampleInvertsTheCdf,
// SlopeSampling.SamplesFollowThePdf, SlopeSampling.StudentTIsGgxAtTwoAndPhongAtOnePlusInverseAlphaSquared,
// IncompleteBeta.ClosedForms), tests/validation/ndf_cross_test.cpp.
// Derivation: docs/derivations/ndf.md.
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
