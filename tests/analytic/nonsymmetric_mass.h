// Test helper: the mass per bounce count k of the nonsymmetric point evaluation (Lee et al. 2018,
// Eq. 23; analytic/brdf_nonsymmetric.h) in 3D, int rho_k(i, o) cos(theta_o) d omega_o over the upper
// hemisphere, for the light at (theta_i, azimuth pi). The quadrature is in h, as in
// tests/analytic/brdf_3d_test.cpp: d omega_o = 4 (i.h) d omega_h cancels the 1/sin(theta_h) of the
// Jacobian printed after Eq. (23); a midpoint grid of n x 4n cells in (theta_h, phi_h). The
// integrand is bounded with jumps along curves and, for k = 1, the NDF's peak at h = n: the error
// falls like 1/n^2 (measured in the tests that use it).
#pragma once

#include "vgroove/analytic/brdf_nonsymmetric.h"

#include <cmath>
#include <numbers>
#include <vector>

namespace vgroove::testing_mass {

// [k], k = 0..max_k (index 0 unused).
inline std::vector<double> point_mass_per_k(const analytic::NonsymmetricModel& m, double theta_i, int n, int max_k) {
  const analytic::Dir3 i = analytic::dir3(theta_i, std::numbers::pi);
  std::vector<double> mass(static_cast<std::size_t>(max_k) + 1, 0.0);
  const double dt = 0.5 * std::numbers::pi / n, dp = 2.0 * std::numbers::pi / (4 * n);
  for (int a = 0; a < n; ++a) {
    const double th = (a + 0.5) * dt;
    for (int b = 0; b < 4 * n; ++b) {
      const analytic::Dir3 h = analytic::dir3(th, (b + 0.5) * dp);
      const double ih = i.x * h.x + i.y * h.y + i.z * h.z;
      const analytic::Dir3 o{2 * ih * h.x - i.x, 2 * ih * h.y - i.y, 2 * ih * h.z - i.z};
      if (!(o.z > 0.0)) continue;
      for (int k = 1; k <= max_k; ++k)
        mass[static_cast<std::size_t>(k)] +=
            analytic::nonsymmetric_brdf_k(i, o, k, m) * o.z * 4.0 * ih * std::sin(th) * dt * dp;
    }
  }
  return mass;
}

}  // namespace vgroove::testing_mass
