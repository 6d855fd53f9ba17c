// vgroove analytic: the Student-T NDF, Ribardiere, Bringier, Meneveaux, Simonot, "STD: Student's
// t-Distribution of Slopes for Microfacet Based BSDFs", CGF 36(2), 2017 (tail gamma > 1.5; gamma = 2
// is GGX, gamma -> infinity Beckmann, gamma = 1 + 1/alpha^2 Phong). One NDF's formulas, written once
// for a double and for four lanes (ndf_math.h), as ndf_ggx.h; derived from the slope law
//   P22(s) = (gamma - 1) c^(gamma-1) / (pi (c + |s|^2)^gamma),  c = (gamma - 1) alpha^2,
// in docs/derivations/student_t.md. With y = c cos^2 / (c cos^2 + sin^2):
//   D = y^gamma / (pi alpha^2 cos^4);  CDF = 1 - y^(gamma-1) over the grooves' area;
//   D2 = sqrt(gamma - 1) Gamma(gamma - 1/2) / (sqrt(pi) Gamma(gamma) alpha) y^(gamma-1/2) / cos^3
//   (a Student-t of 2 gamma - 2 degrees of freedom in the slope);
//   Lambda = A t z^(gamma - 3/2) - I_z(gamma - 1, 1/2) / 2, t = |tan theta_o|, z = c t^2 / (c t^2 + 1).
// Accuracy: the double forms to a few ulp (Lambda: a few ulp times 4 gamma at small t), the vector
// forms within 2 ulp times 2 + gamma |log y| of them (y^gamma by exp and log polynomials). Held by
// tests/analytic/ndf_student_t_test.cpp (normalization, the flatland marginal, Lambda's integral and Smith's projected
// area, the limits and their rates).
#pragma once

#include "vgroove/analytic/ndf_math.h"
#include "vgroove/common/log_gamma_ratio.h"

#include <cmath>
#include <numbers>

namespace vgroove::analytic {

// Regularized incomplete beta function I_x(a, b), x in [0, 1] given with 1 - x (continued fraction,
// Lentz's method; ndf_student_t.cpp).
double incomplete_beta(double a, double b, double x, double one_minus_x);

struct StudentT {
  double alpha;
  double gamma;
  double c = (gamma - 1.0) * alpha * alpha;
  double sqrt_c = std::sqrt(c);

  // y = c cos^2 / (c cos^2 + sin^2) = c / (c + tan^2), in (0, 1].
  template <typename T>
  [[gnu::always_inline]] T y(T cos_m, T sin_m) const {
    const T cc = c * cos_m * cos_m;
    return cc / (cc + sin_m * sin_m);
  }
  template <typename T>
  [[gnu::always_inline]] T D_cs(T cos_m, T sin_m) const {
    const T c2 = cos_m * cos_m;
    return ndf_math::pow(y(cos_m, sin_m), gamma) / (std::numbers::pi * alpha * alpha * c2 * c2);
  }
  double D(double theta_m) const { return D_cs(std::cos(theta_m), std::sin(theta_m)); }
  // D2's factor sqrt(gamma - 1) Gamma(gamma - 1/2) / (sqrt(pi) Gamma(gamma) alpha), the Gammas'
  // ratio through log_gamma_ratio (each overflows beyond gamma ~ 171).
  double D2_norm() const {
    return std::sqrt(gamma - 1.0) * std::exp(log_gamma_ratio(gamma, -0.5)) / (std::sqrt(std::numbers::pi) * alpha);
  }
  template <typename T>
  [[gnu::always_inline]] T D2_cs(T cos_m, T sin_m) const {
    return D2_norm() * ndf_math::pow(y(cos_m, sin_m), gamma - 0.5) / (cos_m * cos_m * cos_m);
  }
  double D2(double theta_m) const { return D2_cs(std::cos(theta_m), std::sin(theta_m)); }

  // The inverse of the CDF over the grooves' area: tan theta_m at u in (0, 1), from log_1mu(), a
  // callable giving log(1 - u).
  static constexpr bool kInverseGivesTan = true;
  template <typename T, typename Log1mu>
  [[gnu::always_inline]] T inverse_cdf(T, Log1mu&& log_1mu) const {
    return alpha * ndf_math::sqrt((gamma - 1.0) * ndf_math::expm1(log_1mu() / (1.0 - gamma)));
  }
  // 1 - (1 + tan^2 / c)^(1 - gamma).
  double cdf(double theta_m) const {
    const double t = std::tan(theta_m);
    return -std::expm1((1.0 - gamma) * std::log1p(t * t / c));
  }

  // The tail of the CDF (the lobe's strata where 1 - u is small): its variable v(1 - u) =
  // log(1 - u), which adds, and from it cot theta_m = 1 / sqrt(c expm1(-v / (gamma - 1))) (the
  // vector form's exponent held at 709: a groove narrower than ~1e-154 rad).
  static constexpr bool kTailArgIsCos = false;
  double tail_variable(double one_minus_u) const { return std::log(one_minus_u); }
  template <typename T>
  [[gnu::always_inline]] T tail_join(double lead, T entry) const {
    return lead + entry;
  }
  template <typename T>
  [[gnu::always_inline]] T tail_arg(T v) const {
    T z = v / (1.0 - gamma);
    if constexpr (!std::is_same_v<T, double>) z = z <= 709.0 ? z : simd::splat(709.0);
    return 1.0 / (sqrt_c * ndf_math::sqrt(ndf_math::expm1(z)));
  }

  // Lambda (the header), 0 at normal view.
  double Lambda(double theta_o) const {
    const double t = std::abs(std::tan(theta_o));
    if (t == 0.0) return 0.0;
    const double ct2 = c * t * t, z = ct2 / (ct2 + 1.0), one_minus_z = 1.0 / (ct2 + 1.0);
    const double A = (gamma - 1.0) * sqrt_c * std::exp(log_gamma_ratio(gamma, -0.5)) /
                     (std::sqrt(std::numbers::pi) * (2.0 * gamma - 3.0));
    return A * t * std::pow(z, gamma - 1.5) - 0.5 * incomplete_beta(gamma - 1.0, 0.5, z, one_minus_z);
  }
  // D is a power of y (no exponential): it underflows only where y^gamma does, at apertures this
  // bound need not list (0: the sums over apertures go on to theta_v = 0).
  double vanishing_aperture() const { return 0.0; }
};

}  // namespace vgroove::analytic
