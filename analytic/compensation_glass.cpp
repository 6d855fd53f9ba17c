// vgroove analytic: Kulla-Conty's rough-glass energy compensation as MoonRay ships it (see the
// header for the source, the conventions and what holds).
#include "vgroove/analytic/compensation_glass.h"

#include "vgroove/analytic/albedo_glass.h"
#include "vgroove/analytic/quadrature.h"
#include "vgroove/optics/fresnel.h"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <vector>

namespace vgroove::analytic {

double kulla_fresnel_average_outside_fit(double N) { return (N - 1.0) / (4.08567 + 1.00071 * N); }

double kulla_fresnel_average_inside_fit(double r) {
  return 0.997118 + 0.1014 * r - 0.965241 * r * r - 0.130607 * r * r * r;
}

BoundedValue dielectric_fresnel_average(double eta, const AlbedoOptions& opt) {
  AdaptiveOptions o;
  o.abs_tol = opt.tol;
  o.max_pieces = opt.max_pieces;
  std::vector<double> cuts;
  const int n = 4 * opt.refine;
  for (int j = 0; j <= n; ++j) cuts.push_back(static_cast<double>(j) / n);
  // Lit from the denser side: F = 1 below the critical cosine sqrt(1 - eta^2), a kink there.
  if (eta < 1.0) {
    cuts.push_back(std::sqrt(1.0 - eta * eta));
    std::sort(cuts.begin(), cuts.end());
  }
  const AdaptiveResult r =
      integrate_adaptive([&](double mu) { return 2.0 * mu * optics::fresnel_dielectric(mu, eta); }, cuts, o);
  return {r.value, r.error, r.converged, r.evaluations};
}

KullaContyGlassAverages kulla_conty_glass_averages_exact(const MicrofacetModel& m, double alpha, double N,
                                                         const AlbedoOptions& opt) {
  KullaContyGlassAverages a;
  a.N = N;
  const GlassAlbedo out = albedo_glass_average(m, alpha, N, opt);
  const GlassAlbedo in = albedo_glass_average(m, alpha, 1.0 / N, opt);
  a.E_avg_out = out.R.value + out.T.value;
  a.E_avg_in = in.R.value + in.T.value;
  a.F_avg_out = dielectric_fresnel_average(N, opt).value;
  a.F_avg_in = dielectric_fresnel_average(1.0 / N, opt).value;
  return a;
}

KullaContyGlassAverages with_kulla_fresnel_fits(KullaContyGlassAverages a) {
  a.F_avg_out = kulla_fresnel_average_outside_fit(a.N);
  a.F_avg_in = kulla_fresnel_average_inside_fit(1.0 / a.N);
  return a;
}

double kulla_conty_glass_split(const KullaContyGlassAverages& a, bool with_N2) {
  const double missing_out = 1.0 - a.E_avg_out;
  if (!(missing_out > 0.0)) return 1.0;  // MoonRay's guard (computeFactor)
  const double scale = with_N2 ? a.N * a.N : 1.0;
  const double t = scale * (1.0 - a.E_avg_in) / missing_out * (1.0 - a.F_avg_in) / (1.0 - a.F_avg_out);
  return std::max(0.0, t / (1.0 + t));
}

KullaContyGlassWeights kulla_conty_glass_weights(double eta, const KullaContyGlassAverages& a, KullaContyGlassForm form,
                                                 bool split_with_N2) {
  const double x = kulla_conty_glass_split(a, split_with_N2);
  KullaContyGlassWeights w;
  if (eta > 1.0) {
    w.transmit = (1.0 - a.F_avg_out) * x;
  } else {
    const double n2 = form == KullaContyGlassForm::moonray ? eta * eta : 1.0;
    w.transmit = n2 * (1.0 - a.F_avg_in) * (1.0 - x);
  }
  // The reflected weight is one minus the unscaled transmitted weight on both sides.
  w.reflect = eta > 1.0 ? 1.0 - w.transmit : 1.0 - (1.0 - a.F_avg_in) * (1.0 - x);
  return w;
}

double kulla_conty_glass_f_ms(double weight, double E_i, double E_o, double E_avg_of_o_side) {
  const double num = (1.0 - E_i) * (1.0 - E_o);
  if (!(num > 0.0) || !(E_avg_of_o_side < 1.0)) return 0.0;  // MoonRay: a zero divisor gives 0
  return std::max(0.0, weight * num / (std::numbers::pi * (1.0 - E_avg_of_o_side)));
}

CompensatedGlass kulla_conty_glass_albedo(double E_R, double E_T, const KullaContyGlassWeights& w) {
  const double missing = std::max(0.0, 1.0 - E_R - E_T);
  return {E_R + w.reflect * missing, E_T + w.transmit * missing};
}

}  // namespace vgroove::analytic
