#include "vgroove/analytic/masking_shadowing.h"

#include "vgroove/analytic/quadrature.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>

namespace vgroove::analytic {

double G2_smith_separable(double lambda_i, double lambda_o) {
  // Heitz 2014, Eq. (20): G1(o) G1(i), G1 = 1 / (1 + Lambda).
  return 1.0 / ((1.0 + lambda_i) * (1.0 + lambda_o));
}

double G2_smith_height_correlated(double lambda_i, double lambda_o) {
  // Heitz 2014, Eq. (21).
  return 1.0 / (1.0 + lambda_i + lambda_o);
}

double van_ginneken_lambda(double phi) {
  // Heitz 2014, Sec. 5 (after Eq. 23), van Ginneken et al. 1998: phi the azimuth difference of
  // the two directions in [0, pi].
  const double p = std::abs(std::remainder(phi, 2.0 * std::numbers::pi));
  return 4.41 * p / (4.41 * p + 1.0);
}

double G2_smith_height_direction_correlated(double lambda_i, double lambda_o, double phi) {
  // Heitz 2014, Eq. (23).
  return 1.0 / (1.0 + std::max(lambda_i, lambda_o) + van_ginneken_lambda(phi) * std::min(lambda_i, lambda_o));
}

double G2_vcavity(double ix, double iy, double iz, double ox, double oy, double oz, double mx, double my, double mz) {
  const double im = ix * mx + iy * my + iz * mz, om = ox * mx + oy * my + oz * mz;
  if (!(im > 0.0 && om > 0.0)) return 0.0;
  return std::min(G1_vcavity(im, iz, mz), G1_vcavity(om, oz, mz));
}

namespace {

// int_bin f(m) D(m) w(m) sin theta_m and the same without f, over panels x panels of 16 x 16 nodes.
template <class W, class F>
double bin_average(NdfKind ndf, double alpha, const NormalBin& bin, int panels, W&& weight, F&& value) {
  static const GaussLegendre g16 = gauss_legendre(16);
  const double dt = (bin.theta_hi - bin.theta_lo) / panels, dp = (bin.phi_hi - bin.phi_lo) / panels;
  double num = 0.0, den = 0.0;
  for (int a = 0; a < panels; ++a)
    for (std::size_t ka = 0; ka < g16.size(); ++ka) {
      const double t = bin.theta_lo + dt * (a + 0.5 * (1.0 + g16.x[ka]));
      const double st = std::sin(t), ct = std::cos(t);
      const double dw_t = 0.5 * dt * g16.w[ka] * D(ndf, t, alpha) * st;
      if (!(dw_t > 0.0)) continue;
      for (int b = 0; b < panels; ++b)
        for (std::size_t kb = 0; kb < g16.size(); ++kb) {
          const double p = bin.phi_lo + dp * (b + 0.5 * (1.0 + g16.x[kb]));
          const double mx = st * std::cos(p), my = st * std::sin(p), mz = ct;
          const double w = dw_t * 0.5 * dp * g16.w[kb] * weight(mx, my, mz);
          if (!(w > 0.0)) continue;
          den += w;
          num += w * value(mx, my, mz);
        }
    }
  return den > 0.0 ? num / den : std::numeric_limits<double>::quiet_NaN();
}

}  // namespace

double vcavity_g1_bin_average(NdfKind ndf, double alpha, double theta_o, double phi_o, const NormalBin& bin,
                              int panels) {
  const double ox = std::sin(theta_o) * std::cos(phi_o), oy = std::sin(theta_o) * std::sin(phi_o),
               oz = std::cos(theta_o);
  return bin_average(
      ndf, alpha, bin, panels,
      [&](double mx, double my, double mz) { return std::max(0.0, ox * mx + oy * my + oz * mz); },
      [&](double mx, double my, double mz) { return G1_vcavity(ox * mx + oy * my + oz * mz, oz, mz); });
}

double vcavity_g2_bin_average(NdfKind ndf, double alpha, double theta_i, double phi_i, double theta_o, double phi_o,
                              const NormalBin& bin, int panels) {
  const double ix = std::sin(theta_i) * std::cos(phi_i), iy = std::sin(theta_i) * std::sin(phi_i),
               iz = std::cos(theta_i);
  const double ox = std::sin(theta_o) * std::cos(phi_o), oy = std::sin(theta_o) * std::sin(phi_o),
               oz = std::cos(theta_o);
  return bin_average(
      ndf, alpha, bin, panels,
      [&](double mx, double my, double mz) {
        return std::max(0.0, ix * mx + iy * my + iz * mz) * std::max(0.0, ox * mx + oy * my + oz * mz);
      },
      [&](double mx, double my, double mz) { return G2_vcavity(ix, iy, iz, ox, oy, oz, mx, my, mz); });
}

}  // namespace vgroove::analytic
