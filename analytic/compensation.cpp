// vgroove analytic: energy compensation formulas (see the header for the sources).
#include "vgroove/analytic/compensation.h"

#include <algorithm>
#include <cmath>
#include <numbers>

namespace vgroove::analytic {

double kulla_conty_f_ms(double E_o, double E_i, double E_avg) {
  const double num = (1.0 - E_o) * (1.0 - E_i);
  // E_avg -> 1 (alpha -> 0): every E -> 1 too and the lobe vanishes; avoid 0/0.
  if (num <= 0.0) return 0.0;
  return num / (std::numbers::pi * (1.0 - E_avg));
}

double kulla_conty_fresnel_factor(double F_avg, double E_avg) {
  // Kulla and Conty 2017: the series F_avg E_avg (F_avg (1 - E_avg))^k summed, times one more
  // F_avg for the first bounce: F_avg^2 E_avg / (1 - F_avg (1 - E_avg)).
  return F_avg * F_avg * E_avg / (1.0 - F_avg * (1.0 - E_avg));
}

double kulla_conty_fresnel_factor_one_bounce_removed(double F_avg, double E_avg) {
  return F_avg * E_avg / (1.0 - F_avg * (1.0 - E_avg));
}

double fresnel_average_schlick(double F0) { return F0 + (1.0 - F0) / 21.0; }

double turquin_factor(double F0, double E_o) { return 1.0 + F0 * (1.0 - E_o) / E_o; }

double filament_energy_compensation(double F0, double dfg_y) { return 1.0 + F0 * (1.0 / dfg_y - 1.0); }

double cycles_energy_factor(double E, double E_avg, double Fss) {
  const double missing = (1.0 - E) / E;
  const double Fms = kulla_conty_fresnel_factor_one_bounce_removed(Fss, E_avg);
  return 1.0 + Fms * missing;
}

double cycles_glass_albedo_scaling(double E, double Fss) { return 1.0 + Fss * ((1.0 - E) / E); }

namespace {
SplitSumScattering split_sum_multi(double FssEss, double Ess, double F0) {
  const double Ems = 1.0 - Ess;
  const double Favg = fresnel_average_schlick(F0);
  const double Fms = FssEss * Favg / (1.0 - Ems * Favg);
  return {FssEss, Fms * Ems};
}
}  // namespace

SplitSumScattering fdez_aguera(double F0, double scale, double bias, double F90) {
  return split_sum_multi(F0 * scale + F90 * bias, scale + bias, F0);
}

SplitSumScattering fdez_aguera_roughness_fresnel(double F0, double scale, double bias, double r, double mu) {
  const double Fr = std::max(1.0 - r, F0) - F0;
  const double kS = F0 + Fr * std::pow(1.0 - mu, 5.0);
  return split_sum_multi(kS * scale + bias, scale + bias, F0);
}

ScaleBias karis_env_brdf_approx(double r, double mu) {
  // Karis 2014, EnvBRDFApprox: c0 = (-1, -0.0275, -0.572, 0.022), c1 = (1, 0.0425, 1.04, -0.04),
  // q = r c0 + c1, a004 = min(q.x^2, 2^(-9.28 mu)) q.x + q.y, (scale, bias) = (-1.04, 1.04) a004 + q.zw.
  const double qx = -r + 1.0, qy = -0.0275 * r + 0.0425, qz = -0.572 * r + 1.04, qw = 0.022 * r - 0.04;
  const double a004 = std::min(qx * qx, std::exp2(-9.28 * mu)) * qx + qy;
  return {-1.04 * a004 + qz, 1.04 * a004 + qw};
}

}  // namespace vgroove::analytic
