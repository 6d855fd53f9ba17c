// vgroove optics: Snell's law, the direction a ray takes across a smooth dielectric interface.
//
// Conventions as optics/fresnel.h: eta is the index of the far medium relative to the near one
// (eta = n_far / n_near > 0), cos_theta_i = |d . m| in [0, 1] (a rounding outside is clamped).
// Snell: sin theta_t = sin theta_i / eta. With sin^2 theta_t written as in
// fresnel_dielectric_polarized, (1 - c)(1 + c) / eta^2, the two agree on total internal reflection
// bit for bit: refract() reports it exactly when fresnel_dielectric returns 1 for that reason.
//
// Header only, on any vector type with .dot() and the arithmetic operators (Eigen's, in sim/).
#pragma once

#include <algorithm>
#include <cmath>

namespace vgroove::optics {

// cos theta_t of the transmitted ray, or -1 under total internal reflection (sin theta_t >= 1).
inline double snell_cos_transmitted(double cos_theta_i, double eta) {
  const double c = std::clamp(cos_theta_i, 0.0, 1.0);
  const double sin2_t = (1.0 - c) * (1.0 + c) / (eta * eta);
  if (sin2_t >= 1.0) return -1.0;
  return std::sqrt(1.0 - sin2_t);
}

// The refracted direction of the unit direction d (travelling) across an interface of unit normal
// m, with m on the near side (d . m <= 0) and eta = n_far / n_near:
//   t = d / eta + (cos_i / eta - cos_t) m,   cos_i = -d . m,
// whose tangential part is d's divided by eta (Snell) and whose normal part is -cos_t m (it goes
// on into the far side). Unit up to rounding. Returns false, t untouched, under total internal
// reflection.
template <class V>
bool refract(const V& d, const V& m, double eta, V& t) {
  const double cos_i = -d.dot(m);
  const double cos_t = snell_cos_transmitted(cos_i, eta);
  if (cos_t < 0.0) return false;
  if (eta == 1.0) {  // index matched: no interface, the ray goes on unchanged (exactly)
    t = d;
    return true;
  }
  const double inv = 1.0 / eta;
  t = inv * d + (inv * std::clamp(cos_i, 0.0, 1.0) - cos_t) * m;
  return true;
}

}  // namespace vgroove::optics
