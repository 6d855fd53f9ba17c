// vgroove analytic: the directional albedo of the 3D V-groove model per bounce order, E_k(mu,
// alpha), with a reflectance per channel: the kaleidoscopic model's exact multiple-scattering
// albedo (the reference the energy audit holds compensation formulas against).
//
// Lee, Jarabo, Jeon, Gutierrez, Kim. "Practical Multiple Scattering for Rough Surfaces". ACM TOG
// 37(6), 2018. Sec. 4.1 (Eq. 4-6), Sec. 5.1 (the 3D surface of grooves, Eq. 10-17), Eq. (11)
// (the energy a path of n reflections keeps, prod_j F(cos theta_j)).
//
// The integral. The grooves of azimuth phi_a (uniform on [0, pi)) and facet angle theta_m take the
// share (1 / pi) du d phi_a of the light, u = CDF(theta_m) of the grooves' area (brdf_3d.h,
// groove_cdf). In a groove the light sees the 2D kaleidoscope at the projected incident angle
// t_i = atan2(-(i.a), i.n), with c = sqrt(1 - (i.u)^2) the length of i's projection (brdf_3d.h).
// Of the light entering the opening 2 sin(theta_v / 2) cos(t_i) (theta_v = pi - 2 theta_m), the
// facet hit first takes its lit width f_a, and of that Eq. (6) sends the fraction G_fewer out after
// K - 1 reflections and G_more after K (Eq. 4, corrected form, ERRATA E1); both facets' shares add
// up to 1. A path of n reflections keeps prod_{j=1..n} F(c |sin((j - 1/2) theta_v - t_f)|) per
// channel (analytic/kaleidoscope_fresnel.h; c times the 2D cosine in 3D, brdf_3d.h), t_f = t_i for
// the left facet first, -t_i for the right. So
//   E_k = (1 / pi) int_0^pi d phi_a int_0^1 du sum_{facet} sum_{outcome with n = k}
//           G f_a / (2 sin(theta_v / 2) cos t_i) prod_j F(...).
// With F = 1, sum_k E_k = 1 (every groove sends all its light out): the white furnace.
//
//
// Quadrature. phi_a over [0, pi/2] with its mirror image (pi - phi_a turns t_i into -t_i and swaps
// the facets: the same energies), by globally adaptive Gauss-Kronrod on the vector of rows (the
// rows have kinks in phi_a where the cuts below cross each other); at normal incidence one
// cross-section serves every azimuth. Per facet, theta_v is cut where Eq. (4) or (6) change form
// (as analytic/lobe_3d.cpp's integrate_band: lit at theta_v = 2 t_f, the f_b clamp at -2 t_f, K at
// (pi + 2 t_f) / j, the f_k clamp at (pi + t_f) / (j - 1/2)) and at the NDF's scale (theta_m =
// atan(alpha 2^j)), down to theta_v = (pi + 2 t_f) / (k_bands + 1), and integrated in theta_v
// itself (the grooves' share pi D cos sin d theta_v is smooth there for every NDF) by band_order
// Gauss-Legendre nodes per piece. Below, the tail (grooves of more than k_bands reflections) takes
// tail_strata midpoints of z = sqrt(1 - u), each groove evaluated exactly. A path's products stop
// once every channel's product is below tail_cutoff, or after 2^20 bounces (a groove that narrow
// holds ~1e-11 of the light at alpha 2): what the path still deposits counts as 0, but in the
// channels whose F is exactly 1 at cos = 0, 1/4, ..., 1 (taken as F = 1: no path's product moves
// them). theta_v is formed as 2 atan(cos theta_m / sin theta_m) in the tail, not pi - 2 theta_m,
// whose absolute rounding times the number of reflections would move the shares of narrow grooves.
// Accuracy (tests/analytic/albedo_vgroove_test.cpp): with F = 1 the total is 1 within 1e-9 and the
// rows agree with the lobe's (analytic/lobe_3d.h, another quadrature of the same model) within
// 2e-7; the defaults against doubled resolution (GGX and Beckmann, alpha 0.05..2, mu 1..0.05, a
// conductor and Schlick's F) move no value by more than 8.3e-9. Cost: 0.06-0.5 s of one core for
// 30 channels (GGX, alpha 0.1..2, mu 0.9 and 0.1).
#pragma once

#include "vgroove/analytic/ndf.h"

#include <functional>
#include <vector>

namespace vgroove::analytic {

// The reflectances of `channels` channels at the cosine of a local angle of incidence, cos in
// [0, 1]: writes out[0..channels-1], each in [0, 1].
using ChannelReflectance = std::function<void(double cos_theta, double* out)>;

struct VgrooveAlbedoOptions {
  double phi_tol = 1e-8;    // the summed |K15 - G7| (largest over the rows and channels) over phi_a
  int phi_max_pieces = 32;  // at most this many Gauss-Kronrod pieces of [0, pi/2]
  int band_order = 8;       // Gauss-Legendre nodes per piece between the cuts
  int k_bands = 24;         // cuts down to the grooves of k_bands reflections; the tail below
  int tail_strata = 256;
  double tail_cutoff = 1e-15;
};

struct VgrooveAlbedo {
  int max_k = 0;
  int channels = 1;
  // [row * channels + c], rows k = 0..max_k + 1 (row 0 is 0: every ray reflects at least once;
  // row max_k + 1 holds every k > max_k).
  std::vector<double> by_k;
  std::vector<double> total;  // [c]: the albedo, the sum of the rows
  double row(int k, int c) const { return by_k[static_cast<std::size_t>(k) * channels + c]; }
};

// E_k(mu, alpha) for mu in (0, 1], alpha > 0, any NDF; F empty: one channel with F = 1.
VgrooveAlbedo vgroove_albedo(NdfKind ndf, double alpha, double mu, int channels, const ChannelReflectance& F, int max_k,
                             const VgrooveAlbedoOptions& opt = {});

}  // namespace vgroove::analytic
