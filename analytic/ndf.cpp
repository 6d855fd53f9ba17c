#include "vgroove/analytic/ndf.h"

#include <algorithm>
#include <cassert>
#include <cmath>
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

double D_beckmann(double theta_m, double alpha) {
  assert(alpha > 0.0);
  if (outside(theta_m)) return 0.0;
  // Walter et al. 2007, Sec. 5 (Heitz 2014, Sec. 3.2):
  //   D(m) = exp(-tan^2 theta_m / alpha^2) / (pi alpha^2 cos^4 theta_m).
  const double c = std::cos(theta_m), t = std::tan(theta_m);
  const double c2 = c * c;
  return std::exp(-(t * t) / (alpha * alpha)) / (std::numbers::pi * alpha * alpha * c2 * c2);
}

double D_ggx(double theta_m, double alpha) {
  assert(alpha > 0.0);
  if (outside(theta_m)) return 0.0;
  // Walter et al. 2007, Sec. 5 (Heitz 2014, Sec. 3.2):
  //   D(m) = alpha^2 / (pi cos^4 (alpha^2 + tan^2)^2) = alpha^2 / (pi (alpha^2 cos^2 + sin^2)^2),
  // the second form finite up to theta_m = pi/2.
  const double c = std::cos(theta_m), s = std::sin(theta_m);
  const double q = alpha * alpha * c * c + s * s;
  return alpha * alpha / (std::numbers::pi * q * q);
}

double D_phong(double theta_m, double alpha) {
  if (outside(theta_m)) return 0.0;
  // Walter et al. 2007, Sec. 5: D(m) = (alpha_p + 2) / (2 pi) cos^alpha_p theta_m;
  // normalized: 2 pi int_0^{pi/2} cos^(p+1) sin = 2 pi / (p + 2).
  const double p = phong_exponent(alpha);
  return (p + 2.0) / (2.0 * std::numbers::pi) * std::pow(std::cos(theta_m), p);
}

double D(NdfKind kind, double theta_m, double alpha) {
  switch (kind) {
    case NdfKind::beckmann:
      return D_beckmann(theta_m, alpha);
    case NdfKind::ggx:
      return D_ggx(theta_m, alpha);
    case NdfKind::phong:
      return D_phong(theta_m, alpha);
  }
  return 0.0;
}

double D_cs(NdfKind kind, double c, double s, double alpha) {
  // The formulas of D_beckmann, D_ggx and D_phong.
  switch (kind) {
    case NdfKind::ggx:
      return D_cs_ggx(c, s, alpha);
    case NdfKind::beckmann: {
      const double t = s / c, c2 = c * c;
      return std::exp(-(t * t) / (alpha * alpha)) / (std::numbers::pi * alpha * alpha * c2 * c2);
    }
    case NdfKind::phong: {
      const double p = phong_exponent(alpha);
      return (p + 2.0) / (2.0 * std::numbers::pi) * std::pow(c, p);
    }
  }
  return 0.0;
}

double D_vanishing_aperture(NdfKind kind, double alpha) {
  switch (kind) {
    case NdfKind::ggx:
      return 0.0;
    case NdfKind::beckmann:
      return 2.0 * std::atan(1.0 / (alpha * std::sqrt(760.0)));
    case NdfKind::phong: {
      const double p = phong_exponent(alpha);
      return p > 0.0 ? 2.0 * std::asin(std::exp(-760.0 / p)) : 0.0;
    }
  }
  return 0.0;
}

double D2_beckmann(double theta_m, double alpha) {
  assert(alpha > 0.0);
  if (outside(theta_m)) return 0.0;
  // P(s) = exp(-s^2/alpha^2) / (sqrt(pi) alpha), the marginal of Beckmann's slopes (ndf.h), and
  // D2 = P(tan theta) / cos^3 theta.
  const double c = std::cos(theta_m), t = std::tan(theta_m);
  return std::exp(-(t * t) / (alpha * alpha)) / (std::sqrt(std::numbers::pi) * alpha * c * c * c);
}

double D2_ggx(double theta_m, double alpha) {
  assert(alpha > 0.0);
  if (outside(theta_m)) return 0.0;
  // P(s) = (1 + s^2/alpha^2)^(-3/2) / (2 alpha), the marginal of GGX's slopes (ndf.h);
  // P(tan) / cos^3 = 1 / (2 alpha (cos^2 + sin^2/alpha^2)^(3/2)) = alpha^2 / (2 q^(3/2)),
  // q = alpha^2 cos^2 + sin^2.
  const double c = std::cos(theta_m), s = std::sin(theta_m);
  const double q = alpha * alpha * c * c + s * s;
  return alpha * alpha / (2.0 * q * std::sqrt(q));
}

double D2_phong(double theta_m, double alpha) {
  if (outside(theta_m)) return 0.0;
  // P(s) = K (1 + s^2)^(-(p+3)/2) (ndf.h), so P(tan)/cos^3 = K cos^(p+3) / cos^3 = K cos^p, and
  // int_{-pi/2}^{pi/2} cos^(p+1) = sqrt(pi) Gamma((p+2)/2) / Gamma((p+3)/2) = 1/K.
  // Through lgamma: both Gammas overflow for alpha below about 0.08 (p/2 > 171).
  const double p = phong_exponent(alpha);
  const double K = std::exp(std::lgamma(0.5 * (p + 3.0)) - std::lgamma(0.5 * (p + 2.0))) / std::sqrt(std::numbers::pi);
  return K * std::pow(std::cos(theta_m), p);
}

double D2(NdfKind kind, double theta_m, double alpha) {
  switch (kind) {
    case NdfKind::beckmann:
      return D2_beckmann(theta_m, alpha);
    case NdfKind::ggx:
      return D2_ggx(theta_m, alpha);
    case NdfKind::phong:
      return D2_phong(theta_m, alpha);
  }
  return 0.0;
}

double D2_cs(NdfKind kind, double c, double s, double alpha) {
  // The formulas of D2_beckmann, D2_ggx and D2_phong.
  if (!(c > 0.0)) return 0.0;
  switch (kind) {
    case NdfKind::ggx: {
      const double q = alpha * alpha * c * c + s * s;
      return alpha * alpha / (2.0 * q * std::sqrt(q));
    }
    case NdfKind::beckmann: {
      const double t = s / c;
      return std::exp(-(t * t) / (alpha * alpha)) / (std::sqrt(std::numbers::pi) * alpha * c * c * c);
    }
    case NdfKind::phong: {
      const double p = phong_exponent(alpha);
      const double K =
          std::exp(std::lgamma(0.5 * (p + 3.0)) - std::lgamma(0.5 * (p + 2.0))) / std::sqrt(std::numbers::pi);
      return K * std::pow(c, p);
    }
  }
  return 0.0;
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
  const double t = std::abs(std::tan(theta_o));
  if (t == 0.0) return 0.0;  // a = infinity: nothing is masked at normal view
  const double a = 1.0 / (alpha * t);
  // Heitz 2014, Sec. 3.2: Lambda = (erf(a) - 1)/2 + exp(-a^2) / (2 a sqrt(pi)); erf(a) - 1 is
  // written -erfc(a), which keeps its digits when a is large (Lambda ~ e^-a^2 / a^3 there).
  return -0.5 * std::erfc(a) + std::exp(-a * a) / (2.0 * a * std::sqrt(std::numbers::pi));
}

double Lambda_ggx(double theta_o, double alpha) {
  assert(alpha > 0.0);
  // Heitz 2014, Sec. 3.2: Lambda = (-1 + sqrt(1 + 1/a^2)) / 2 with 1/a^2 = alpha^2 tan^2;
  // written x / (2 (1 + sqrt(1 + x))), x = 1/a^2, which does not cancel for small x.
  const double t = std::tan(theta_o);
  const double x = alpha * alpha * t * t;
  return x / (2.0 * (1.0 + std::sqrt(1.0 + x)));
}

double Lambda(NdfKind kind, double theta_o, double alpha) {
  assert(kind == NdfKind::beckmann || kind == NdfKind::ggx);
  return kind == NdfKind::ggx ? Lambda_ggx(theta_o, alpha) : Lambda_beckmann(theta_o, alpha);
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
