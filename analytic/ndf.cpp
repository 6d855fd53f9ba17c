#include "vgroove/analytic/ndf.h"

#include "vgroove/analytic/ndf_visit.h"

#include <algorithm>
#include <cassert>
#include <cmath>
#include <limits>
#include <numbers>

namespace vgroove::analytic {

double phong_exponent(double alpha) {
  assert(alpha > 0.0);
  // Walter et al. 2007, Sec. 5: alpha_p = 2 alpha_b^-2 - 2.
  return 2.0 / (alpha * alpha) - 2.0;
}

namespace {
// |theta_m| >= pi/2: a facet facing sideways or down is no facet of a height field (chi+).
bool outside(double theta_m) { return !(std::abs(theta_m) < 0.5 * std::numbers::pi); }
}  // namespace

// Each D below is the NDF's own formula (ndf_ggx.h, ndf_beckmann.h, ndf_phong.h) inside the
// horizon.
double D_beckmann(double theta_m, double alpha) {
  assert(alpha > 0.0);
  return outside(theta_m) ? 0.0 : Beckmann{alpha}.D(theta_m);
}

double D_ggx(double theta_m, double alpha) {
  assert(alpha > 0.0);
  return outside(theta_m) ? 0.0 : Ggx{alpha}.D(theta_m);
}

double D_phong(double theta_m, double alpha) { return outside(theta_m) ? 0.0 : Phong{alpha}.D(theta_m); }

double D(NdfKind kind, double theta_m, double alpha) {
  if (outside(theta_m)) return 0.0;
  return visit_ndf(kind, alpha, [&](const auto& ndf) { return ndf.D(theta_m); });
}

double D_cs(NdfKind kind, double c, double s, double alpha) {
  return visit_ndf(kind, alpha, [&](const auto& ndf) { return ndf.D_cs(c, s); });
}

double D_vanishing_aperture(NdfKind kind, double alpha) {
  return visit_ndf(kind, alpha, [](const auto& ndf) { return ndf.vanishing_aperture(); });
}

double D2_beckmann(double theta_m, double alpha) {
  assert(alpha > 0.0);
  return outside(theta_m) ? 0.0 : Beckmann{alpha}.D2(theta_m);
}

double D2_ggx(double theta_m, double alpha) {
  assert(alpha > 0.0);
  return outside(theta_m) ? 0.0 : Ggx{alpha}.D2(theta_m);
}

double D2_phong(double theta_m, double alpha) { return outside(theta_m) ? 0.0 : Phong{alpha}.D2(theta_m); }

double D2(NdfKind kind, double theta_m, double alpha) {
  if (outside(theta_m)) return 0.0;
  return visit_ndf(kind, alpha, [&](const auto& ndf) { return ndf.D2(theta_m); });
}

double D2_cs(NdfKind kind, double c, double s, double alpha) {
  if (!(c > 0.0)) return 0.0;
  return visit_ndf(kind, alpha, [&](const auto& ndf) { return ndf.D2_cs(c, s); });
}

double G1_vcavity(double o_dot_h, double o_dot_n, double h_dot_n) {
  // Lee et al. 2018, Eq. (2): G1(o, h) = H(o.h / o.n) min(1, 2 |h.n| |o.n| / |o.h|).
  // H(x) = 0 for x <= 0: a facet seen edge-on (o.h = 0) shows no area.
  if (!(o_dot_h / o_dot_n > 0.0)) return 0.0;
  return std::min(1.0, 2.0 * std::abs(h_dot_n) * std::abs(o_dot_n) / std::abs(o_dot_h));
}

double G1_vcavity_inplane(double theta_o, double theta_h) {
  return G1_vcavity(std::cos(theta_o - theta_h), std::cos(theta_o), std::cos(theta_h));
}

double Lambda_beckmann(double theta_o, double alpha) {
  assert(alpha > 0.0);
  return Beckmann{alpha}.Lambda(theta_o);
}

double Lambda_ggx(double theta_o, double alpha) {
  assert(alpha > 0.0);
  return Ggx{alpha}.Lambda(theta_o);
}

double Lambda(NdfKind kind, double theta_o, double alpha) {
  assert(kind != NdfKind::phong);
  assert(alpha > 0.0);
  return visit_ndf(kind, alpha, [&](const auto& ndf) {
    if constexpr (requires { ndf.Lambda(theta_o); }) {
      return ndf.Lambda(theta_o);
    } else {
      return std::numeric_limits<double>::quiet_NaN();  // Phong: no closed form
    }
  });
}

double G1_smith_beckmann(double theta_o, double alpha) {
  // Heitz 2014, Eq. (10).
  return 1.0 / (1.0 + Lambda_beckmann(theta_o, alpha));
}

double G1_smith_ggx(double theta_o, double alpha) {
  // Heitz 2014, Eq. (10).
  return 1.0 / (1.0 + Lambda_ggx(theta_o, alpha));
}

}  // namespace vgroove::analytic
