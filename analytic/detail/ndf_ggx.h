// vgroove analytic: GGX (Trowbridge-Reitz), Walter et al. 2007, Sec. 5; Heitz 2014, Sec. 3.2 (the
// papers and conventions: ndf.h). One NDF's formulas, written once for a double and for four lanes
// (ndf_math.h); ndf.cpp, brdf_3d.cpp and the lobe's kernels call them through visit_ndf (ndf_visit.h).
//   D(m)  = alpha^2 / (pi cos^4 (alpha^2 + tan^2)^2) = alpha^2 / (pi q^2), q = alpha^2 cos^2 + sin^2
//           (finite up to theta_m = pi/2);
//   D2    = alpha^2 / (2 q^(3/2))  (the slope marginal (1 + s^2/alpha^2)^(-3/2) / (2 alpha), ndf.h);
//   CDF   = tan^2 / (alpha^2 + tan^2) over the grooves' area, so tan theta_m = alpha sqrt(u / (1 - u));
//   Lambda = (-1 + sqrt(1 + alpha^2 tan^2)) / 2.
#pragma once

#include "vgroove/analytic/detail/ndf_math.h"

#include <cmath>
#include <numbers>

namespace vgroove::analytic {

struct Ggx {
  double alpha;

  // q = alpha^2 cos^2 + sin^2 (the batched BRDF pass sums W / q^2 and applies alpha^2 / pi once).
  template <typename T>
  [[gnu::always_inline]] T q(T cos_m, T sin_m) const {
    return alpha * alpha * cos_m * cos_m + sin_m * sin_m;
  }
  template <typename T>
  [[gnu::always_inline]] T D_cs(T cos_m, T sin_m) const {
    const T qm = q(cos_m, sin_m);
    return alpha * alpha / (std::numbers::pi * qm * qm);
  }
  double D(double theta_m) const { return D_cs(std::cos(theta_m), std::sin(theta_m)); }
  template <typename T>
  [[gnu::always_inline]] T D2_cs(T cos_m, T sin_m) const {
    const T qm = q(cos_m, sin_m);
    return alpha * alpha / (2.0 * qm * ndf_math::sqrt(qm));
  }
  double D2(double theta_m) const { return D2_cs(std::cos(theta_m), std::sin(theta_m)); }

  // The inverse of the CDF over the grooves' area: tan theta_m at u in (0, 1) (log_1mu, a callable
  // giving log(1 - u), is not needed).
  static constexpr bool kInverseGivesTan = true;
  template <typename T, typename Log1mu>
  [[gnu::always_inline]] T inverse_cdf(T u, Log1mu&&) const {
    return alpha * ndf_math::sqrt(u / (1.0 - u));
  }
  double cdf(double theta_m) const {
    const double t = std::tan(theta_m), t2 = t * t;
    return t2 / (alpha * alpha + t2);
  }

  // The tail of the CDF (the lobe's strata where 1 - u is small): its variable v(1 - u) = 1 - u,
  // which multiplies (v(m s) = v(m) v(s)), and from it cot theta_m = sqrt(v / (1 - v)) / alpha.
  static constexpr bool kTailArgIsCos = false;
  double tail_variable(double one_minus_u) const { return one_minus_u; }
  template <typename T>
  [[gnu::always_inline]] T tail_join(double lead, T entry) const {
    return lead * entry;
  }
  template <typename T>
  [[gnu::always_inline]] T tail_arg(T v) const {
    return ndf_math::sqrt(v / (1.0 - v)) / alpha;
  }

  // Lambda with x = alpha^2 tan^2 as x / (2 (1 + sqrt(1 + x))), which does not cancel for small x.
  double Lambda(double theta_o) const {
    const double t = std::tan(theta_o);
    const double x = alpha * alpha * t * t;
    return x / (2.0 * (1.0 + std::sqrt(1.0 + x)));
  }
  // D never underflows (a power law): no aperture below which it is 0.
  double vanishing_aperture() const { return 0.0; }
};

}  // namespace vgroove::analytic
