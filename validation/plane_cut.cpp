#include "vgroove/validation/plane_cut.h"

#include "vgroove/validation/report.h"

#include <cmath>
#include <numbers>

namespace vgroove::validation {

PlaneCut::PlaneCut(int theta_bins, int phi_bins)
    : theta_bins_(theta_bins),
      phi_bins_(phi_bins),
      width_(phi_bins == 0 ? std::numbers::pi / theta_bins : 0.5 * std::numbers::pi / theta_bins) {}

double PlaneCut::solid_angle(int t) const {
  const double dp = 2.0 * std::numbers::pi / phi_bins_;
  return dp * (std::cos(t * width_) - std::cos((t + 1) * width_));
}

std::vector<double> PlaneCut::angles_deg() const {
  std::vector<double> out;
  if (phi_bins_ == 0) {
    for (int b = 0; b < theta_bins_; ++b) out.push_back(output_deg(-0.5 * std::numbers::pi + (b + 0.5) * width_));
    return out;
  }
  for (int t = theta_bins_ - 1; t >= 0; --t) out.push_back(output_deg(-(t + 0.5) * width_));
  for (int t = 0; t < theta_bins_; ++t) out.push_back(output_deg((t + 0.5) * width_));
  return out;
}

}  // namespace vgroove::validation
