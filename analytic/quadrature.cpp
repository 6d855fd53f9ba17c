#include "vgroove/analytic/quadrature.h"

#include <cmath>
#include <numbers>

namespace vgroove::analytic {

GaussLegendre gauss_legendre(int n) {
  GaussLegendre g;
  g.x.assign(static_cast<std::size_t>(n), 0.0);
  g.w.assign(static_cast<std::size_t>(n), 0.0);
  for (int i = 0; i < n; ++i) {
    double z = std::cos(std::numbers::pi * (i + 0.75) / (n + 0.5));  // the i-th root from the top
    double dp = 1.0;
    for (int it = 0; it < 100; ++it) {
      double p0 = 1.0, p1 = z;  // P_{j-1}, P_j
      for (int j = 2; j <= n; ++j) {
        const double p2 = ((2.0 * j - 1.0) * z * p1 - (j - 1.0) * p0) / j;
        p0 = p1;
        p1 = p2;
      }
      if (n == 1) p0 = 1.0;
      dp = n * (z * p1 - p0) / (z * z - 1.0);  // P_n'(z)
      const double dz = p1 / dp;
      z -= dz;
      if (std::abs(dz) < 1e-16) break;
    }
    g.x[static_cast<std::size_t>(i)] = -z;
    g.w[static_cast<std::size_t>(i)] = 2.0 / ((1.0 - z * z) * dp * dp);
  }
  return g;
}

const GaussLegendre& gauss_legendre_cached(int n) {
  static const GaussLegendre r2 = gauss_legendre(2), r4 = gauss_legendre(4), r8 = gauss_legendre(8);
  return n == 2 ? r2 : (n == 4 ? r4 : r8);
}

}  // namespace vgroove::analytic
