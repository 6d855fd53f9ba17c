#include "vgroove/validation/histogram_metrics.h"

#include <algorithm>
#include <cmath>
#include <numbers>

namespace vgroove::validation {

double sum(const std::vector<double>& v) {
  double s = 0.0;
  for (double x : v) s += x;
  return s;
}

bool all_finite(const std::vector<double>& v) {
  return std::all_of(v.begin(), v.end(), [](double x) { return std::isfinite(x); });
}

double l1(const std::vector<double>& a, const std::vector<double>& b) {
  double s = 0.0;
  for (std::size_t n = 0; n < a.size(); ++n) s += std::abs(a[n] - b[n]);
  return s;
}

std::vector<double> normalized(std::vector<double> v) {
  const double s = sum(v);
  if (s > 0.0)
    for (double& x : v) x /= s;
  return v;
}

ExpectedL1 expected_l1(const std::vector<double>& p, double rays, double grooves) {
  const double inv = 1.0 / rays + (grooves > 0.0 ? 1.0 / grooves : 0.0);
  double mean = 0.0, var = 0.0;
  for (double q : p) {
    const double v = std::max(0.0, q * (1.0 - q)) * inv;
    mean += std::sqrt(2.0 * v / std::numbers::pi);
    var += (1.0 - 2.0 / std::numbers::pi) * v;
  }
  return {mean, std::sqrt(var)};
}

}  // namespace vgroove::validation
