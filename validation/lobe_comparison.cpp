#include "vgroove/validation/lobe_comparison.h"

#include "vgroove/validation/histogram_metrics.h"

#include <algorithm>
#include <cmath>
#include <cstddef>

namespace vgroove::validation {

L1Test l1_test(double l1, const std::vector<double>& p, double rays, double grooves, double sigmas, double tolerance) {
  const ExpectedL1 e = expected_l1(p, rays, grooves);
  return {l1, e.mean, e.mean + sigmas * e.sd + tolerance};
}

double albedo_threshold(double albedo_model, double rays, double grooves, double sigmas, double tolerance) {
  const double a = std::clamp(albedo_model, 0.0, 1.0);
  return sigmas * std::sqrt(a * (1.0 - a) * (1.0 / rays + 1.0 / grooves)) + 1.0 / rays + tolerance;
}

std::vector<double> bin_totals(const std::vector<double>& joint, int bins) {
  const auto width = static_cast<std::size_t>(bins);
  std::vector<double> total(width, 0.0);
  for (std::size_t n = 0; n < joint.size(); ++n) total[n % width] += joint[n];
  return total;
}

LobeComparison compare_lobes(const std::vector<double>& sim_joint, const std::vector<double>& model_joint, int bins,
                             double rays, double grooves, double sigmas, double tolerance) {
  LobeComparison c;
  c.sim_shape = normalized(bin_totals(sim_joint, bins));
  const std::vector<double> p = normalized(bin_totals(model_joint, bins));
  c.shape = l1_test(l1(c.sim_shape, p), p, rays, grooves, sigmas, tolerance);
  c.joint = l1_test(l1(sim_joint, model_joint), model_joint, rays, grooves, sigmas, tolerance);
  return c;
}

}  // namespace vgroove::validation
