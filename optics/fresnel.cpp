#include "vgroove/optics/fresnel.h"

#include <algorithm>
#include <cassert>
#include <cmath>
#include <complex>
#include <limits>

namespace vgroove::optics {

namespace {
// |d . n| of two unit vectors can exceed 1 by a rounding; outside [0, 1] the formulas would
// describe no physical angle.
double clamp_cos(double c) { return std::clamp(c, 0.0, 1.0); }

// |a|^2 / |b|^2. The squares underflow when |b| is below 1e-154 (eta = 1e-300 at normal
// incidence: n^2 c and w = n both tiny), where the quotient of the moduli is still exact; and
// with b = 0 (n = 0: a perfect conductor) the reflectance is its limit, 1.
double ratio_of_norms(const std::complex<double>& a, const std::complex<double>& b) {
  const double nb = std::norm(b);
  if (nb >= std::numeric_limits<double>::min()) return std::norm(a) / nb;
  const double mb = std::abs(b);
  if (mb == 0.0) return 1.0;
  const double q = std::abs(a) / mb;
  return q * q;
}
}  // namespace

PolarizedReflectance fresnel_conductor_polarized(double cos_theta_i, double eta, double kappa) {
  assert(eta > 0.0 && kappa >= 0.0);
  const double c = clamp_cos(cos_theta_i);
  // Index matched: no interface, nothing reflected (and 0/0 below at grazing incidence).
  if (eta == 1.0 && kappa == 0.0) return {0.0, 0.0};
  // n^2 for n = eta + i kappa, written out (the same values as n * n, without the library's
  // NaN-recovery path for complex products).
  const std::complex<double> n2(eta * eta - kappa * kappa, 2.0 * eta * kappa);
  const double sin2 = (1.0 - c) * (1.0 + c);  // 1 - c^2 without cancellation near c = 1
  // w = n cos(theta_t) = sqrt(n^2 - sin^2 theta_i); Im(n^2) = 2 eta kappa >= 0, so the principal
  // root has Im w >= 0 (a decaying transmitted wave).
  const std::complex<double> w = std::sqrt(n2 - sin2);
  // |r|^2 as |numerator|^2 / |denominator|^2: one real division, no complex one.
  PolarizedReflectance r;
  r.s = ratio_of_norms(c - w, c + w);
  r.p = ratio_of_norms(n2 * c - w, n2 * c + w);
  return r;
}

double fresnel_conductor(double cos_theta_i, double eta, double kappa) {
  return fresnel_conductor_polarized(cos_theta_i, eta, kappa).unpolarized();
}

PolarizedReflectance fresnel_dielectric_polarized(double cos_theta_i, double eta) {
  assert(eta > 0.0);
  const double c = clamp_cos(cos_theta_i);
  if (eta == 1.0) return {0.0, 0.0};  // index matched, as above
  const double sin2_t = (1.0 - c) * (1.0 + c) / (eta * eta);
  if (sin2_t >= 1.0) return {1.0, 1.0};  // total internal reflection (eta < 1, sin theta_i >= eta)
  const double cos_t = std::sqrt(1.0 - sin2_t);
  const double rs = (c - eta * cos_t) / (c + eta * cos_t);
  const double rp = (eta * c - cos_t) / (eta * c + cos_t);
  return {rs * rs, rp * rp};
}

double fresnel_dielectric(double cos_theta_i, double eta) {
  return fresnel_dielectric_polarized(cos_theta_i, eta).unpolarized();
}

double fresnel_schlick(double cos_theta_i, double F0) {
  const double m = 1.0 - clamp_cos(cos_theta_i);
  const double m2 = m * m;
  return F0 + (1.0 - F0) * (m2 * m2 * m);
}

double fresnel_normal_incidence(double eta, double kappa) {
  const double k2 = kappa * kappa;
  return ((eta - 1.0) * (eta - 1.0) + k2) / ((eta + 1.0) * (eta + 1.0) + k2);
}

}  // namespace vgroove::optics
