#include "vgroove/analytic/bounce_percentiles.h"

#include "vgroove/analytic/brdf_3d.h"
#include "vgroove/analytic/kaleidoscope.h"
#include "vgroove/analytic/quadrature.h"

#include <cassert>
#include <cmath>
#include <numbers>

namespace vgroove::analytic {

const char* percentile_measure_name(PercentileMeasure m) {
  switch (m) {
    case PercentileMeasure::projected_area:
      return "projected_area";
    case PercentileMeasure::solid_angle:
      return "solid_angle";
    case PercentileMeasure::flatland:
      return "flatland";
  }
  return "?";
}

namespace {

// The unnormalized density of theta in [0, pi/2) under each measure.
double density(NdfKind ndf, double alpha, double theta, PercentileMeasure m) {
  switch (m) {
    case PercentileMeasure::projected_area:
      return 2.0 * std::numbers::pi * D(ndf, theta, alpha) * std::cos(theta) * std::sin(theta);
    case PercentileMeasure::solid_angle:
      return 2.0 * std::numbers::pi * D(ndf, theta, alpha) * std::sin(theta);
    case PercentileMeasure::flatland:
      return 2.0 * D2(ndf, theta, alpha) * std::cos(theta);
  }
  return 0.0;
}

// Integral of the density over [0, theta]: composite 5-point Gauss-Legendre on equal panels. The
// densities are smooth on [0, pi/2) and bounded (D cos^4 is bounded for the three NDFs, so
// D sin may grow like 1/cos^4 only for GGX's solid-angle measure near pi/2: integrable, and
// resolved by the panels to far below the percentile's sensitivity here).
double integral(NdfKind ndf, double alpha, double theta, PercentileMeasure m) {
  static const GaussLegendre rule = gauss_legendre(5);
  constexpr int panels = 400;
  const double h = theta / panels;
  double s = 0.0;
  for (int p = 0; p < panels; ++p) {
    const double c = (p + 0.5) * h;
    for (std::size_t n = 0; n < rule.size(); ++n) s += rule.w[n] * density(ndf, alpha, c + 0.5 * h * rule.x[n], m);
  }
  return 0.5 * h * s;
}

double numeric_quantile(NdfKind ndf, double alpha, double q, PercentileMeasure m) {
  // The solid-angle density of GGX grows like 1/cos^2 towards pi/2 (D ~ 1/(cos^4 tan^4)); its
  // total is still finite. Normalize by the integral up to just below pi/2.
  const double top = 0.5 * std::numbers::pi * (1.0 - 1e-9);
  const double total = integral(ndf, alpha, top, m);
  double lo = 0.0, hi = top;
  for (int it = 0; it < 60; ++it) {
    const double mid = 0.5 * (lo + hi);
    (integral(ndf, alpha, mid, m) < q * total ? lo : hi) = mid;
  }
  return 0.5 * (lo + hi);
}

}  // namespace

double theta_m_quantile(NdfKind ndf, double alpha, double q, PercentileMeasure m) {
  assert(alpha > 0.0 && q > 0.0 && q < 1.0);
  if (m != PercentileMeasure::projected_area) return numeric_quantile(ndf, alpha, q, m);
  switch (ndf) {
    case NdfKind::ggx:
      return std::atan(alpha * std::sqrt(q / (1.0 - q)));
    case NdfKind::beckmann:
      return std::atan(alpha * std::sqrt(-std::log1p(-q)));
    case NdfKind::phong:
      return std::acos(std::pow(1.0 - q, 1.0 / (phong_exponent(alpha) + 2.0)));
    case NdfKind::student_t:
      return groove_cdf_inverse(ndf, alpha, q);
  }
  return 0.0;
}

int max_bounces_at_percentile(NdfKind ndf, double alpha, double q, PercentileMeasure m) {
  const double theta_m = theta_m_quantile(ndf, alpha, q, m);
  return bounce_count(0.0, std::numbers::pi - 2.0 * theta_m);  // Lee et al. 2018, Eq. (4) at theta_i = 0
}

}  // namespace vgroove::analytic
