#include "vgroove/analytic/kaleidoscope_nonsymmetric.h"

#include <algorithm>
#include <cmath>
#include <numbers>

namespace vgroove::analytic {

double aperture(double theta_l, double theta_r) { return std::numbers::pi + theta_l - theta_r; }

int bounce_count_kb(double theta_i, double theta_l, double theta_r) {
  // Lee et al. 2018, Eq. (7).
  const double theta_v = aperture(theta_l, theta_r);
  return saturate_to_int(2.0 *
                         std::floor((std::numbers::pi + 2.0 * theta_i - (theta_l + theta_r)) / (2.0 * theta_v) + 0.5));
}

double exit_angle_nonsymmetric(double theta_i, double theta_l, double theta_r, int k) {
  // Lee et al. 2018, Eq. (8).
  const double mean = 0.5 * (theta_l + theta_r);
  const double sign = (k % 2 == 0) ? 1.0 : -1.0;
  return std::remainder(sign * (theta_i - mean + std::numbers::pi - k * aperture(theta_l, theta_r)) + mean,
                        2.0 * std::numbers::pi);
}

double exit_angle_nonsymmetric(double theta_i, double theta_l, double theta_r, int k, FacetSide first) {
  // Mirroring (Sec. 4.2): theta_i -> -theta_i, theta_l -> -theta_r, theta_r -> -theta_l; o back.
  return first == FacetSide::left ? exit_angle_nonsymmetric(theta_i, theta_l, theta_r, k)
                                  : -exit_angle_nonsymmetric(-theta_i, -theta_r, -theta_l, k);
}

namespace {
NonsymmetricPrediction left_first(double theta_i, double theta_l, double theta_r) {
  NonsymmetricPrediction p;
  const double theta_v = aperture(theta_l, theta_r);
  // Facet lengths: equal rim heights, l_L sin(-theta_l) = l_R sin(theta_r); the longer is 1.
  // A facet at 0 deg has no height, so the other has no length; both at 0 is the flat mirror.
  const double h_l = std::sin(-theta_l), h_r = std::sin(theta_r), h_max = std::max(h_l, h_r);
  const double len_l = h_max > 0.0 ? h_r / h_max : 1.0, len_r = h_max > 0.0 ? h_l / h_max : 1.0;
  const double phi_a = theta_l + 0.5 * std::numbers::pi;  // angle of the left rim a from n
  // f of fan vertex P_j (the circle alternates with j), and of the right rim b = P_{-1}.
  auto f_vertex = [&](int j) {
    const double len = (j % 2 == 0) ? len_l : len_r;
    return len * std::sin(phi_a + j * theta_v - theta_i);
  };
  p.f_a = f_vertex(0);
  p.lit = p.f_a > 0.0;
  if (!p.lit) return p;
  // "we can define f_a, f_b, f_k,a and f_k,b using max(0, f(p))" (Sec. 4.2).
  p.f_b = std::max(0.0, len_r * std::sin(phi_a - theta_v - theta_i));
  p.k_b = bounce_count_kb(theta_i, theta_l, theta_r);
  p.f_2 = std::max(0.0, f_vertex(1));
  p.f_kb = std::max(0.0, f_vertex(p.k_b - 1));
  p.f_ka = std::max(0.0, f_vertex(p.k_b));
  const double fa = p.f_a, fb = p.f_b;
  // Lee et al. 2018, Eq. (9).
  const double G[4] = {
      std::max(0.0, fa - std::max(p.f_2, fb)) / fa,
      std::max(0.0, std::min(fa, p.f_2) - p.f_kb) / fa,
      std::max(0.0, std::min(fa, p.f_kb) - std::max(p.f_ka, fb)) / fa,
      std::max(0.0, std::min(p.f_kb, p.f_ka) - fb) / fa,
  };
  const int n[4] = {1, p.k_b - 1, p.k_b, p.k_b + 1};
  for (int z = 0; z < 4; ++z) p.share[z] = {n[z], G[z], exit_angle_nonsymmetric(theta_i, theta_l, theta_r, n[z])};
  p.shadow = fb / fa;
  return p;
}
}  // namespace

NonsymmetricPrediction G_nonsymmetric(double theta_i, double theta_l, double theta_r, FacetSide first) {
  if (first == FacetSide::left) return left_first(theta_i, theta_l, theta_r);
  NonsymmetricPrediction p = left_first(-theta_i, -theta_r, -theta_l);
  if (p.lit)
    for (BounceShare& s : p.share) s.theta_o = exit_angle_nonsymmetric(theta_i, theta_l, theta_r, s.n, first);
  return p;
}

double dtheta_h_dtheta_l(int k) {
  // d/d theta_l of Eq. (8): (-1)^k (-1/2 - k) + 1/2; theta_h moves at half that rate.
  const double sign = (k % 2 == 0) ? 1.0 : -1.0;
  return 0.5 * (0.5 - sign * (k + 0.5));
}

double jacobian_ds_l_do(double theta_sl, double theta_h, double theta_d, int k) {
  // Lee et al. 2018, after Eq. (23).
  return std::sin(theta_sl) / (std::abs(dtheta_h_dtheta_l(k)) * std::sin(theta_h)) / (4.0 * std::cos(theta_d));
}

}  // namespace vgroove::analytic
