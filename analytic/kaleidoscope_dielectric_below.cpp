#include "vgroove/analytic/kaleidoscope_dielectric_below.h"

#include <algorithm>
#include <cmath>

namespace vgroove::analytic {

double DielectricBelowPrediction::reflected_total() const {
  double s = 0.0;
  for (const BelowLobe& l : lobes)
    if (!l.up) s += l.share;
  return s;
}

double DielectricBelowPrediction::transmitted_total() const {
  double s = 0.0;
  for (const BelowLobe& l : lobes)
    if (l.up) s += l.share;
  return s;
}

FlatBelowPrediction flat_rim_below(double theta_i, double eta) {
  FlatBelowPrediction f;
  const double c = std::cos(theta_i);
  f.tir = detail::total_internal_reflection(c, 1.0 / eta);
  f.F = f.tir ? 1.0 : optics::fresnel_dielectric(c, 1.0 / eta);
  f.theta_r = -theta_i;
  if (!f.tir) f.theta_t = std::asin(std::clamp(eta * std::sin(theta_i), -1.0, 1.0));
  return f;
}

void rim_line_interval_below(double theta_i, double theta_v, FacetSide side, double& lo, double& hi) {
  // The lines through the facet: from its rim (x = -+sin(theta_v/2)) to the one through the apex,
  // which crosses the rim line y = cos(theta_v/2) at -cos(theta_v/2) tan(theta_i).
  const double x_apex = -std::cos(0.5 * theta_v) * std::tan(theta_i);
  const double x_rim = std::sin(0.5 * theta_v);
  if (side == FacetSide::left) {
    lo = -x_rim, hi = x_apex;
  } else {
    lo = x_apex, hi = x_rim;
  }
}

BelowBeamShares below_beam_shares(double theta_i, double theta_v, double lo, double hi) {
  BelowBeamShares b;
  const double width = hi - lo;
  if (!(width > 0.0)) return b;
  double rest = 1.0;
  for (FacetSide side : {FacetSide::left, FacetSide::right}) {
    const double t = side == FacetSide::left ? theta_i : -theta_i;
    if (!(std::sin(0.5 * theta_v - t) > 0.0)) continue;  // not lit (the model's test)
    double a = 0.0, z = 0.0;
    rim_line_interval_below(theta_i, theta_v, side, a, z);
    // Every ray whose line crosses a lit facet meets it first (from below the groove is a convex
    // wedge, and the rims lie above every facet point): KD-5.
    const double overlap = std::max(0.0, std::min(z, hi) - std::max(a, lo));
    b.facet[static_cast<int>(side)] = overlap / width;
    rest -= overlap / width;
  }
  b.flat = rest;
  return b;
}

DielectricBelowPrediction kaleidoscope_dielectric_below(double theta_i, double theta_v, double eta, FacetSide first) {
  return kaleidoscope_dielectric_below_with(
      theta_i, theta_v, eta, first, [](double c, double eta_rel) { return optics::fresnel_dielectric(c, eta_rel); });
}

}  // namespace vgroove::analytic
