// vgroove optics: Fresnel reflectance of a smooth interface, for unpolarized light, and Schlick's
// approximation. Lee et al. 2018 ("Practical Multiple Scattering for Rough Surfaces", ACM TOG
// 37(6)), Eq. (11) and Eq. (23)'s R term use "the standard Fresnel reflection equation", written
// out here: F = (|r_s|^2 + |r_p|^2) / 2 with w = sqrt(n^2 - sin^2 theta_i), n = eta + i kappa the
// far medium's index relative to the near one (principal root: decay into an absorber, total
// internal reflection for kappa = 0, eta < 1). cos_theta_i in [0, 1] (a rounding outside is
// clamped). A leaf module (<cmath>, <complex>): sim/ and analytic/ may both include it.
// Tests: tests/optics/fresnel_test.cpp (Fresnel.NormalIncidenceIsTheClosedForm,
// Fresnel.TotalInternalReflectionBeyondTheCriticalAngle, Fresnel.BrewsterAngleZeroesThePPolarization,
// Fresnel.HandDerivedValuesAtFortyFiveDegrees, Fresnel.ConductorAgreesWithTheRealArithmeticForm,
// Fresnel.ExtremeIndicesGiveFiniteFractions), tests/optics/metals_reference_test.cpp.
// Derivation: docs/derivations/kaleidoscope.md.
#pragma once

namespace vgroove::optics {

// Power reflectances of the two polarizations: R_s = |r_s|^2 (E perpendicular to the plane of
// incidence), R_p = |r_p|^2 (E in it).
struct PolarizedReflectance {
  double s = 0.0;
  double p = 0.0;
  double unpolarized() const { return 0.5 * (s + p); }
};

// Conductor (or any medium) of complex relative index eta + i kappa, eta > 0, kappa >= 0.
PolarizedReflectance fresnel_conductor_polarized(double cos_theta_i, double eta, double kappa);
double fresnel_conductor(double cos_theta_i, double eta, double kappa);

// Dielectric of real relative index eta > 0 (eta < 1: light inside the denser medium; beyond the
// critical angle sin theta_i > eta, total internal reflection gives 1).
PolarizedReflectance fresnel_dielectric_polarized(double cos_theta_i, double eta);
double fresnel_dielectric(double cos_theta_i, double eta);

// Schlick's approximation: F0 + (1 - F0) (1 - cos theta_i)^5, exact at normal incidence by
// construction (F0 is the normal reflectance) and 1 at grazing incidence.
double fresnel_schlick(double cos_theta_i, double F0);

// Reflectance at normal incidence, ((eta - 1)^2 + kappa^2) / ((eta + 1)^2 + kappa^2): Schlick's F0.
double fresnel_normal_incidence(double eta, double kappa = 0.0);

}  // namespace vgroove::optics
