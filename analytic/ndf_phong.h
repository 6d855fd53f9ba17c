// vgroove analytic: Phong, Walter et al. 2007, Sec. 5, with the exponent p = 2 / alpha^2 - 2 that
// matches Beckmann's width alpha (the papers and conventions: ndf.h). One NDF's formulas, written
// once for a double and for four lanes (ndf_math.h); ndf.cpp, brdf_3d.cpp and the lobe's kernels
// call them through visit_ndf (ndf_visit.h).
//   D(m)  = (p + 2) / (2 pi) cos^p  (normalized: 2 pi int cos^(p+1) sin = 2 pi / (p + 2));
//   D2    = K cos^p, K = Gamma((p+3)/2) / (sqrt(pi) Gamma((p+2)/2))  (the slope marginal, ndf.h);
//   CDF   = 1 - cos^(p+2) over the grooves' area, so 1 - cos theta_m = 1 - (1 - u)^(1/(p+2)).
// No closed-form Lambda: Phong is not shape invariant (Heitz 2014, Sec. 3.2).
#pragma once

#include "vgroove/analytic/ndf_math.h"
#include "vgroove/common/log_gamma_ratio.h"

#include <cmath>
#include <numbers>

namespace vgroove::analytic {

struct Phong {
  double alpha;
  double p = 2.0 / (alpha * alpha) - 2.0;  // Walter et al. 2007, Sec. 5: alpha_p = 2 alpha^-2 - 2

  template <typename T>
  [[gnu::always_inline]] T D_c(T cos_m) const {
    return (p + 2.0) / (2.0 * std::numbers::pi) * ndf_math::pow(cos_m, p);
  }
  template <typename T>
  [[gnu::always_inline]] T D_cs(T cos_m, T) const {
    return D_c(cos_m);
  }
  double D(double theta_m) const { return D_c(std::cos(theta_m)); }
  // K through log_gamma_ratio: both Gammas overflow for alpha below about 0.08 (p/2 > 171).
  double D2_norm() const { return std::exp(log_gamma_ratio(0.5 * (p + 2.0), 0.5)) / std::sqrt(std::numbers::pi); }
  template <typename T>
  [[gnu::always_inline]] T D2_cs(T cos_m, T) const {
    return D2_norm() * ndf_math::pow(cos_m, p);
  }
  double D2(double theta_m) const { return D2_norm() * std::pow(std::cos(theta_m), p); }

  // The inverse of the CDF over the grooves' area: 1 - cos theta_m at u in (0, 1), from log_1mu(),
  // a callable giving log(1 - u): -expm1(log(1 - u) / (p + 2)), exact for small angles.
  static constexpr bool kInverseGivesTan = false;
  template <typename T, typename Log1mu>
  [[gnu::always_inline]] T inverse_cdf(T, Log1mu&& log_1mu) const {
    return -ndf_math::expm1(log_1mu() / (p + 2.0));
  }
  // 1 - cos^(p+2) with log cos = log1p(-2 sin^2(theta/2)), which keeps small angles exact.
  double cdf(double theta_m) const {
    const double s = std::sin(0.5 * theta_m);
    return -std::expm1((p + 2.0) * std::log1p(-2.0 * s * s));
  }

  // The tail of the CDF (the lobe's strata where 1 - u is small): its variable v(1 - u) =
  // (1 - u)^(1/(p+2)) = cos theta_m, which multiplies (v(m s) = v(m) v(s)).
  static constexpr bool kTailArgIsCos = true;
  double tail_variable(double one_minus_u) const { return std::pow(one_minus_u, 1.0 / (p + 2.0)); }
  template <typename T>
  [[gnu::always_inline]] T tail_join(double lead, T entry) const {
    return lead * entry;
  }
  template <typename T>
  [[gnu::always_inline]] T tail_arg(T v) const {
    return v;
  }

  // cos^p = 0 once p log(cos) < -745.2, at theta_v < 2 asin(exp(-760 / p)) (ndf.h,
  // D_vanishing_aperture); never for p <= 0.
  double vanishing_aperture() const { return p > 0.0 ? 2.0 * std::asin(std::exp(-760.0 / p)) : 0.0; }
};

}  // namespace vgroove::analytic
