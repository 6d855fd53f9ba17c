// vgroove optics: Fresnel reflectance of a smooth interface, for unpolarized light.
//
// Lee, Jarabo, Jeon, Gutierrez, Kim. "Practical Multiple Scattering for Rough Surfaces".
// ACM TOG 37(6), 2018, Eq. (11): the energy a k-bounce path keeps is the product of F at each
// bounce's local angle (and Eq. (23)'s R term for nonsymmetric grooves). The paper uses "the
// standard Fresnel reflection equation"; this file writes it out.
//
// A leaf module (<cmath>, <complex> only): both sim/ and analytic/ may include it.
//
// Conventions. cos_theta_i is the cosine of the angle between the incident ray and the surface
// normal, in [0, 1] (callers pass |d . n|); values a rounding outside are clamped into [0, 1].
// eta + i kappa is the index of the far medium relative to the near one (kappa >= 0 absorbs).
// The unpolarized reflectance is the mean of the s and p power reflectances,
//   F = (|r_s|^2 + |r_p|^2) / 2,
// and the amplitudes follow from w = n cos(theta_t) = sqrt(n^2 - sin^2 theta_i) (Snell's law,
// n = eta + i kappa):
//   r_s = (cos theta_i - w) / (cos theta_i + w),   r_p = (n^2 cos theta_i - w) / (n^2 cos theta_i + w).
// (r_p's sign convention varies between texts; |r_p|^2 does not.) The principal square root
// gives Im w >= 0, the wave that decays into an absorbing medium, and for kappa = 0, eta < 1
// beyond the critical angle w = i |w| (total internal reflection, |r_s| = |r_p| = 1).
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
