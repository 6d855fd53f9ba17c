#include "vgroove/analytic/ndf_anisotropic.h"

#include <cmath>

namespace vgroove::analytic {

double alpha_along(const Roughness& r, double phi) {
  if (r.isotropic()) return r.alpha_x;
  const double c = std::cos(phi) / r.alpha_x, s = std::sin(phi) / r.alpha_y;
  return 1.0 / std::sqrt(c * c + s * s);
}

double D_anisotropic(const Roughness& r, double theta_m, double phi_m) {
  if (r.isotropic()) return D(r.ndf, theta_m, r.alpha_x);
  const double a = alpha_along(r, phi_m);
  // Heitz 2014, Sec. 5.3, along one azimuth (header).
  return a * a / (r.alpha_x * r.alpha_y) * D(r.ndf, theta_m, a);
}

}  // namespace vgroove::analytic
