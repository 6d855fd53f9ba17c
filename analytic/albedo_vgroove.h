// vgroove analytic: the directional albedo of the 3D V-groove model per bounce order, E_k(mu,
// alpha), with a reflectance per channel: the kaleidoscopic model's exact multiple-scattering
// albedo (the reference the energy audit holds compensation formulas against). Lee et al. 2018
// ("Practical Multiple Scattering for Rough Surfaces", ACM TOG 37(6)), Sec. 4.1 (Eq. 4-6), Sec.
// 5.1 (Eq. 10-17), Eq. (11) (prod_j F(cos theta_j) per path):
//   E_k = (1/pi) int dphi_a int du sum_facet sum_{n = k} G f_a / (2 sin(theta_v/2) cos t_i) prod_j F.
// Quadrature: adaptive Gauss-Kronrod over phi_a, Gauss-Legendre in theta_v cut where Eq. (4), (6)
// change form, a stratified tail. Accuracy: with F = 1 the total is 1 within 1e-9, the rows agree
// with analytic/lobe_3d.h's within 2e-7, doubled resolution moves no value by more than 8.3e-9.
// Tests: tests/analytic/albedo_vgroove_test.cpp (AlbedoVgroove.WhiteFurnaceAndTheLobesRows,
// AlbedoVgroove.DoubledResolutionMovesNoValueBeyondTheStatedAccuracy,
// AlbedoVgroove.FirstRowIsCookTorrancesAlbedoWithTheVcavityG, AlbedoVgroove.ExtremesStayFinite).
// Timings: docs/performance.md. Derivation: docs/derivations/albedo.md.
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
