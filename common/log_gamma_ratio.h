// vgroove common: log(Gamma(a + b) / Gamma(a)) for a > 0, a + b > 0, |b| <= 1, to a few ulp of the
// result where lgamma(a + b) - lgamma(a) loses log2(|lgamma(a)|) bits (1e-11 relative at a = 1e4).
// The normalization of the t laws (Student-T, Phong) and the incomplete beta function's front
// factor take it. Held by tests/common/log_gamma_ratio_test.cpp (against Boost.Math's
// tgamma_delta_ratio).
//
// Below a = 20 the recurrence Gamma(a + b) / Gamma(a) = Gamma(a + 1 + b) / Gamma(a + 1) a / (a + b)
// moves a up (one rounding per step); from 20 on, Stirling's series for both Gammas, their
// difference written without cancellation:
//   (a - 1/2) log1p(b / a) + b log(a + b) - b + s(a + b) - s(a),
//   s(x) = 1/(12 x) - 1/(360 x^3) + 1/(1260 x^5) - 1/(1680 x^7) + 1/(1188 x^9)
// (its next term, 691 / (360360 x^11), is below 1e-17 at x = 20).
#pragma once

#include <cmath>

namespace vgroove {

inline double log_gamma_ratio(double a, double b) {
  double product = 1.0;
  for (; a < 20.0; a += 1.0) product *= a / (a + b);
  auto s = [](double x) {
    const double r = 1.0 / x, r2 = r * r;
    return r * (1.0 / 12.0 - r2 * (1.0 / 360.0 - r2 * (1.0 / 1260.0 - r2 * (1.0 / 1680.0 - r2 / 1188.0))));
  };
  return (a - 0.5) * std::log1p(b / a) + b * std::log(a + b) - b + (s(a + b) - s(a)) + std::log(product);
}

}  // namespace vgroove
