// vgroove analytic: the kaleidoscopic model for nonsymmetric V-grooves: Lee et al. 2018,
// "Practical Multiple Scattering for Rough Surfaces", Sec. 4.2, Eq. (7)-(9). Conventions as in
// analytic/kaleidoscope.h. The facet angles are those of the inward normals: theta_l < 0 (the left
// facet leans right), theta_r > 0, aperture theta_v = |pi + theta_l - theta_r|; only these signs
// reduce Eq. (8) to Eq. (5) in the symmetric limit. Both rims at one height, the longer facet of
// unit length. The transition points, not printed, follow from the unfolded fan (ERRATA E2).
// Tests: tests/analytic/kaleidoscope_nonsymmetric_test.cpp (KaleidoscopeNonsymmetric.SymmetricGroovesReduceToEq4To6,
// KaleidoscopeNonsymmetric.SharesAreFractionsThatSumToOne, KaleidoscopeNonsymmetric.MirrorImageSwapsTheFacets,
// KaleidoscopeNonsymmetric.RightAngleCornerHandValues), against the tracer
// tests/validation/nonsymmetric_test.cpp (NonsymmetricTrace.RandomGroovesOffTheGrid).
// Derivation: docs/derivations/kaleidoscope.md.
#pragma once

#include "vgroove/analytic/kaleidoscope.h"

namespace vgroove::analytic {

// Aperture theta_v = pi + theta_l - theta_r (Fig. 5).
double aperture(double theta_l, double theta_r);

// Eq. (7): k_b = 2 floor((pi + 2 theta_i - (theta_l + theta_r)) / (2 theta_v) + 0.5); k_a = k_b + 1.
int bounce_count_kb(double theta_i, double theta_l, double theta_r);

// Eq. (8): exit angle after k reflections, light hitting the left facet first, wrapped into (-pi, pi].
double exit_angle_nonsymmetric(double theta_i, double theta_l, double theta_r, int k);
// The same for light hitting `first` first (the right facet by the paper's mirroring).
double exit_angle_nonsymmetric(double theta_i, double theta_l, double theta_r, int k, FacetSide first);

// The model's prediction for the rays aimed at one facet, normalized by its projected width f_a.
struct NonsymmetricPrediction {
  bool lit = false;
  int k_b = 0;  // Eq. (7)
  double f_a = 0, f_b = 0, f_2 = 0, f_ka = 0, f_kb = 0;
  // Eq. (9)'s zones: 1, k_b - 1, k_b, k_b + 1 reflections (two may share a count when k_b = 2).
  BounceShare share[4] = {{0, 0.0, 0.0}, {0, 0.0, 0.0}, {0, 0.0, 0.0}, {0, 0.0, 0.0}};
  double shadow = 0.0;  // f_b / f_a
};

// Eq. (9) for the rays aimed at `first`. Requires theta_l <= 0 <= theta_r and a positive aperture.
NonsymmetricPrediction G_nonsymmetric(double theta_i, double theta_l, double theta_r, FacetSide first);

// d theta_h / d theta_l at fixed theta_r and k, from Eq. (8) with theta_h = (theta_i + theta_o) / 2:
// 0.5 (0.5 - (-1)^k (k + 0.5)). Its reciprocal is the angular factor of the Jacobian printed after
// Eq. (23); docs/ERRATA.md records the check against the tracer.
double dtheta_h_dtheta_l(int k);

// The Jacobian |ds_l/do| as printed after Eq. (23):
// sin(theta_sl) / (0.5 |0.5 - (-1)^k (k + 0.5)| sin(theta_h)) * 1 / (4 cos(theta_d)).
double jacobian_ds_l_do(double theta_sl, double theta_h, double theta_d, int k);

}  // namespace vgroove::analytic
