// Tests of common/log_gamma_ratio.h against Boost.Math's tgamma_delta_ratio (an independent
// implementation: Gamma(a) / Gamma(a + delta) by Lanczos approximations), over the arguments the
// t laws use (b = 1/2, -1/2 and the Phong exponents' shifts) and a from 0.1 to 1e8.
#include "vgroove/common/log_gamma_ratio.h"

#include <gtest/gtest.h>
#include <boost/math/special_functions/gamma.hpp>

#include <cmath>

namespace vgroove {
namespace {

// Within 4 ulp of the result's magnitude (at least 1): the recurrence's roundings below 20 and
// Stirling's terms above. lgamma(a + b) - lgamma(a) misses this by 1e-11 relative at a = 1e4 (seen
// failing with it in place of the series).
TEST(LogGammaRatio, AgreesWithBoostMath) {
  for (double b : {0.5, -0.5, 1.0, 0.25, -0.9})
    for (double a : {0.1, 0.6, 1.0, 1.5, 3.7, 10.0, 19.5, 20.0, 20.5, 47.3, 1e3, 1e4 + 0.5, 3e5, 1e8}) {
      if (!(a + b > 0.0)) continue;
      const double ref = -std::log(boost::math::tgamma_delta_ratio(a, b));
      EXPECT_NEAR(log_gamma_ratio(a, b), ref, 8.9e-16 * std::max(1.0, std::abs(ref))) << "a=" << a << " b=" << b;
    }
}

// Gamma(a + 1) / Gamma(a) = a exactly (the recurrence itself), at a where the series runs.
TEST(LogGammaRatio, ShiftByOneIsTheArgument) {
  for (double a : {25.0, 300.0, 12345.0}) EXPECT_NEAR(log_gamma_ratio(a, 1.0), std::log(a), 4e-16 * std::log(a)) << a;
}

}  // namespace
}  // namespace vgroove
