// vgroove analytic: Beckmann, Walter et al. 2007, Sec. 5; Heitz 2014, Sec. 3.2 (the papers and
// conventions: ndf.h). One NDF's formulas, written once for a double and for four lanes (ndf_math.h);
// ndf.cpp, brdf_3d.cpp and the lobe's kernels call them through visit_ndf (ndf_visit.h).
//   D(m)  = exp(-tan^2 / alpha^2) / (pi alpha^2 cos^4);
//   D2    = exp(-tan^2 / alpha^2) / (sqrt(pi) alpha cos^3)  (the Gaussian slope marginal, ndf.h);
//   CDF   = 1 - exp(-tan^2 / alpha^2) over the grooves' area, so tan theta_m = alpha sqrt(-log(1 - u));
//   Lambda = (erf(a) - 1) / 2 + exp(-a^2) / (2 a sqrt(pi)), a = 1 / (alpha |tan theta_o|).
#pragma once

#include "vgroove/analytic/detail/ndf_math.h"

#include <cmath>
#include <numbers>

namespace vgroove::analytic {

struct Beckmann {
  double alpha;

  // From cos theta_m and tan theta_m (the vector forms are 0 where tan^2 / alpha^2 > 708).
  template <typename T>
  [[gnu::always_inline]] T D_ct(T cos_m, T tan_m) const {
    const T c2 = cos_m * cos_m;
    return ndf_math::exp_nonpositive(-(tan_m * tan_m) / (alpha * alpha)) / (std::numbers::pi * alpha * alpha * c2 * c2);
  }
  template <typename T>
  [[gnu::always_inline]] T D_cs(T cos_m, T sin_m) const {
    return D_ct(cos_m, sin_m / cos_m);
  }
  double D(double theta_m) const { return D_ct(std::cos(theta_m), std::tan(theta_m)); }
  template <typename T>
  [[gnu::always_inline]] T D2_ct(T cos_m, T tan_m) const {
    return ndf_math::exp_nonpositive(-(tan_m * tan_m) / (alpha * alpha)) /
           (std::sqrt(std::numbers::pi) * alpha * cos_m * cos_m * cos_m);
  }
  template <typename T>
  [[gnu::always_inline]] T D2_cs(T cos_m, T sin_m) const {
    return D2_ct(cos_m, sin_m / cos_m);
  }
  double D2(double theta_m) const { return D2_ct(std::cos(theta_m), std::tan(theta_m)); }

  // The inverse of the CDF over the grooves' area: tan theta_m at u in (0, 1), from log_1mu(), a
  // callable giving log(1 - u).
  static constexpr bool kInverseGivesTan = true;
  template <typename T, typename Log1mu>
  [[gnu::always_inline]] T inverse_cdf(T, Log1mu&& log_1mu) const {
    return alpha * ndf_math::sqrt(-log_1mu());
  }
  double cdf(double theta_m) const {
    const double t = std::tan(theta_m), t2 = t * t;
    return -std::expm1(-t2 / (alpha * alpha));
  }

  // The tail of the CDF (the lobe's strata where 1 - u is small): its variable v(1 - u) =
  // log(1 - u), which adds (v(m s) = v(m) + v(s)), and from it cot theta_m = 1 / (alpha sqrt(-v)).
  static constexpr bool kTailArgIsCos = false;
  double tail_variable(double one_minus_u) const { return std::log(one_minus_u); }
  template <typename T>
  [[gnu::always_inline]] T tail_join(double lead, T entry) const {
    return lead + entry;
  }
  template <typename T>
  [[gnu::always_inline]] T tail_arg(T v) const {
    return 1.0 / (alpha * ndf_math::sqrt(-v));
  }

  // erf(a) - 1 is written -erfc(a), which keeps its digits when a is large (Lambda ~ e^-a^2 / a^3).
  double Lambda(double theta_o) const {
    const double t = std::abs(std::tan(theta_o));
    if (t == 0.0) return 0.0;  // a = infinity: nothing is masked at normal view
    const double a = 1.0 / (alpha * t);
    return -0.5 * std::erfc(a) + std::exp(-a * a) / (2.0 * a * std::sqrt(std::numbers::pi));
  }
  // exp(-tan^2/alpha^2) = 0 once tan^2/alpha^2 > 745.2, at theta_v < 2 atan(1 / (alpha sqrt(760)))
  // (ndf.h, D_vanishing_aperture).
  double vanishing_aperture() const { return 2.0 * std::atan(1.0 / (alpha * std::sqrt(760.0))); }
};

}  // namespace vgroove::analytic
