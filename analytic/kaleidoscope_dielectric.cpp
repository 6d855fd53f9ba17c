#include "vgroove/analytic/kaleidoscope_dielectric.h"

#include <algorithm>
#include <cmath>
#include <numbers>

namespace vgroove::analytic {

double chain_direction(double theta_i, double theta_v, int j, FacetSide first) {
  // Eq. (5) with n = j - 1: the direction after j - 1 reflections (n = 0: the incident -i).
  return exit_angle(theta_i, theta_v, j - 1, first);
}

bool refracted_angle(double theta_i, double theta_v, double eta, int j, FacetSide first, double& theta_t) {
  // Left facet first; the right one by mirroring (theta_i -> -theta_i, theta_t -> -theta_t).
  const double t = first == FacetSide::left ? theta_i : -theta_i;
  const double beta = (j - 0.5) * theta_v - t;                   // KD-2: the unfolded angle; cos alpha_j = |sin beta|
  const double c = local_cos_theta(theta_i, theta_v, j, first);  // Eq. (11): |sin beta|
  // Snell (optics/snell.h's test, so the two agree on total internal reflection):
  // sin^2 theta_t = (1 - c)(1 + c) / eta^2.
  if ((1.0 - c) * (1.0 + c) / (eta * eta) >= 1.0) return false;
  const double sign = (j % 2 == 1) ? 1.0 : -1.0;  // s_j = (-1)^(j - 1): the left facet at odd j
  // KD-3: theta_t = s_j (asin(sin alpha_j s_j / eta) + mu_j s_j), sin alpha_j = s_j cos beta,
  // mu_j = -s_j (pi - theta_v) / 2.
  const double a = sign * (std::asin(std::clamp(std::cos(beta) / eta, -1.0, 1.0)) - 0.5 * (std::numbers::pi - theta_v));
  theta_t = first == FacetSide::left ? a : -a;
  return true;
}

double DielectricFacetPrediction::transmitted_total() const {
  double s = 0.0;
  for (const TransmittedLobe& t : transmitted) s += t.share;
  return s;
}

double DielectricFacetPrediction::indirect_total() const {
  double s = 0.0;
  for (const TransmittedLobe& t : transmitted)
    if (!t.direct) s += t.share;
  return s;
}

DielectricFacetPrediction kaleidoscope_dielectric(double theta_i, double theta_v, double eta, FacetSide first) {
  return kaleidoscope_dielectric_with(theta_i, theta_v, eta, first,
                                      [eta](double c) { return optics::fresnel_dielectric(c, eta); });
}

}  // namespace vgroove::analytic
