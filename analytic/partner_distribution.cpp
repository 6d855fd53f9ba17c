#include "vgroove/analytic/partner_distribution.h"

#include <cmath>
#include <numbers>
#include <stdexcept>
#include <string>

namespace vgroove::analytic {

namespace {
void require_partner_law(NdfKind ndf, double alpha) {
  if (!partner_law_exists(ndf, alpha))
    throw std::domain_error("P(theta_r) does not exist for " + std::string(ndf_name(ndf)) +
                            " alpha = " + std::to_string(alpha) + " (Phong needs alpha < sqrt(2))");
}
bool inside(double theta_r) { return theta_r >= 0.0 && theta_r < 0.5 * std::numbers::pi; }
}  // namespace

bool partner_law_exists(NdfKind ndf, double alpha) {
  if (!(alpha > 0.0)) return false;
  if (ndf == NdfKind::student_t) return false;  // not written for Student-T
  return ndf != NdfKind::phong || phong_exponent(alpha) > -1.0;
}

double P_theta_r_normalization(NdfKind ndf, double alpha) {
  require_partner_law(ndf, alpha);
  const double sqrt_pi = std::sqrt(std::numbers::pi);
  switch (ndf) {
    case NdfKind::beckmann:
      return alpha / (4.0 * sqrt_pi);
    case NdfKind::ggx:
      return alpha / 4.0;
    case NdfKind::phong: {
      // (p+2)/(2 pi) int_0^{pi/2} cos^p sin^2 = (p+2)/(2 pi) B(3/2, (p+1)/2) / 2, through lgamma
      // (the Gammas overflow for small alpha).
      const double p = phong_exponent(alpha);
      return (p + 2.0) / (8.0 * sqrt_pi) * std::exp(std::lgamma(0.5 * (p + 1.0)) - std::lgamma(0.5 * (p + 4.0)));
    }
    case NdfKind::student_t:
      break;  // refused by require_partner_law
  }
  return 0.0;
}

double P_theta_r(NdfKind ndf, double theta_r, double alpha) {
  const double N = P_theta_r_normalization(ndf, alpha);
  if (!inside(theta_r)) return 0.0;
  const double s = std::sin(theta_r);
  // Lee et al. 2018, Eq. (20).
  return D(ndf, theta_r, alpha) * s * s / N;
}

double P_theta_r_printed(NdfKind ndf, double theta_r, double alpha) {
  require_partner_law(ndf, alpha);
  if (!inside(theta_r)) return 0.0;
  const double sqrt_pi = std::sqrt(std::numbers::pi);
  double c = 0.0;
  // Lee et al. 2018, App. C, as printed.
  switch (ndf) {
    case NdfKind::beckmann:
      c = alpha / (2.0 * sqrt_pi);
      break;
    case NdfKind::ggx:
      c = alpha / 4.0;
      break;
    case NdfKind::phong: {
      const double p = phong_exponent(alpha);
      c = (p + 2.0) / (8.0 * sqrt_pi) *
          std::exp(std::lgamma(0.5 * (p + 1.0)) + std::lgamma(0.5 * (p + 3.0)) - std::lgamma(0.5 * (p + 4.0)));
      break;
    }
    case NdfKind::student_t:
      break;  // refused by require_partner_law
  }
  const double s = std::sin(theta_r);
  return c * D(ndf, theta_r, alpha) * s * s;
}

double P2_theta_r_normalization(NdfKind ndf, double alpha) {
  require_partner_law(ndf, alpha);
  switch (ndf) {
    case NdfKind::beckmann:
      return alpha / (2.0 * std::sqrt(std::numbers::pi));
    case NdfKind::ggx:
      return alpha / 2.0;
    case NdfKind::phong: {
      // D2 = K cos^p (analytic/ndf.cpp) and int_0^{pi/2} cos^p sin = 1 / (p + 1).
      const double p = phong_exponent(alpha);
      const double K =
          std::exp(std::lgamma(0.5 * (p + 3.0)) - std::lgamma(0.5 * (p + 2.0))) / std::sqrt(std::numbers::pi);
      return K / (p + 1.0);
    }
    case NdfKind::student_t:
      break;  // refused by require_partner_law
  }
  return 0.0;
}

double P2_theta_r(NdfKind ndf, double theta_r, double alpha) {
  const double N2 = P2_theta_r_normalization(ndf, alpha);
  if (!inside(theta_r)) return 0.0;
  return D2(ndf, theta_r, alpha) * std::sin(theta_r) / N2;
}

}  // namespace vgroove::analytic
