#include "vgroove/analytic/kaleidoscope_fresnel.h"

#include "vgroove/analytic/kaleidoscope_nonsymmetric.h"

#include <cmath>

namespace vgroove::analytic {

double local_cos_theta(double theta_i, double theta_v, int j, FacetSide first) {
  // The unfolded fan (kaleidoscope_fresnel.h): line j at theta_v/2 + (j - 1) theta_v.
  const double t = first == FacetSide::left ? theta_i : -theta_i;
  return std::abs(std::sin((j - 0.5) * theta_v - t));
}

double local_cos_theta_nonsymmetric(double theta_i, double theta_l, double theta_r, int j, FacetSide first) {
  const double theta_v = aperture(theta_l, theta_r);
  // Left first: line j along theta_l + pi/2 + (j - 1) theta_v; |sin(theta_i - that)| = |cos(...)|.
  if (first == FacetSide::left) return std::abs(std::cos(theta_i - theta_l - (j - 1) * theta_v));
  // Right first: the mirror image, groove (-theta_r, -theta_l) and -theta_i.
  return std::abs(std::cos(theta_i - theta_r + (j - 1) * theta_v));
}

}  // namespace vgroove::analytic
