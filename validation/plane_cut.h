// vgroove validation: the plane of incidence cut out of a binned lobe, for plots.
//
// Flatland lobes hold flatland_bins equal bins of theta_o over (-pi/2, pi/2): the cut is every
// bin, as a density per radian. 3D lobes hold theta_bins x phi_bins bins (theta_o over
// [0, pi/2), phi_o centred on the mirror azimuth, phi_bins even): the cut is phi bin 0 (the
// mirror side, as the signed angle -theta_o, the flatland convention) from the horizon down, then
// phi bin phi_bins/2 (towards the light, +theta_o) from the normal up, as densities per steradian.
// Tested by tests/validation/plane_cut_test.cpp.
#pragma once

#include <cstddef>
#include <vector>

namespace vgroove::validation {

class PlaneCut {
 public:
  static PlaneCut flatland(int bins) { return PlaneCut(bins, 0); }
  static PlaneCut three_d(int theta_bins, int phi_bins) { return PlaneCut(theta_bins, phi_bins); }

  // The bins of one row of the lobe.
  int bins() const { return phi_bins_ == 0 ? theta_bins_ : theta_bins_ * phi_bins_; }
  // The signed exit angle of each point of the cut, degrees (validation/report.h output_deg).
  std::vector<double> angles_deg() const;
  // value(n) / measure(n) at each point of the cut, n the lobe bin (within one row).
  template <class Value>
  std::vector<double> cut(Value&& value) const {
    std::vector<double> out;
    if (phi_bins_ == 0) {
      for (int b = 0; b < theta_bins_; ++b) out.push_back(value(static_cast<std::size_t>(b)) / width_);
      return out;
    }
    for (int t = theta_bins_ - 1; t >= 0; --t)
      out.push_back(value(static_cast<std::size_t>(t) * phi_bins_) / solid_angle(t));
    for (int t = 0; t < theta_bins_; ++t)
      out.push_back(value(static_cast<std::size_t>(t) * phi_bins_ + phi_bins_ / 2) / solid_angle(t));
    return out;
  }

 private:
  PlaneCut(int theta_bins, int phi_bins);
  double solid_angle(int t) const;
  int theta_bins_, phi_bins_;
  double width_;  // flatland: the bin width; 3D: the theta bin width
};

}  // namespace vgroove::validation
