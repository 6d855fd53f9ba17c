// Distance in units in the last place, for the tests of the polynomial sines and arctangents
// (analytic/detail/sin_batch.h, analytic/detail/atan_pair.h) against long double.
#pragma once

#include <cmath>

namespace vgroove::test_ulps {

// |a - b| in units of the last place of b (the exact value, in long double) rounded to a double.
inline double ulps(double a, long double b) {
  const double bd = static_cast<double>(b);
  const double ulp = std::nextafter(std::abs(bd), INFINITY) - std::abs(bd);
  return static_cast<double>(std::abs(static_cast<long double>(a) - b) / ulp);
}

}  // namespace vgroove::test_ulps
