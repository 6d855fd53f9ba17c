// vgroove analytic: one cross-section problem of the kaleidoscopic dielectric model (the light's
// projected angle, the index ratio its directions follow, the 3D local cosine over the 2D one, TIR of
// the whole section), flatland or lifted from 3D, as the binned lobe, the point BSDF and the sampler
// share it (kaleidoscope_dielectric_lobe.h, kaleidoscope_dielectric_point.h, sampling_dielectric.h).
// Lifting: docs/derivations/dielectric_lifting.md (the effective index sqrt(eta^2 - q^2) / sqrt(1 - q^2)
// and the 3D local angle cos = r_1 cos').
// Tests: tests/analytic/kaleidoscope_dielectric_lobe_test.cpp (KaleidoscopeDielectricLobe.*),
// tests/analytic/kaleidoscope_dielectric_point_test.cpp (KaleidoscopeDielectricPoint.*),
// tests/analytic/sampling_dielectric_test.cpp (SamplingDielectric.*).
#pragma once

#include <cmath>

namespace vgroove::analytic {

struct DielectricSection {
  double tau = 0.0;      // the projected angle of the light (towards it), analytic/kaleidoscope.h's theta_i
  double eta_dir = 1.5;  // the index ratio of the directions: eta, or the lifted law's effective one
  double c3d = 1.0;      // the 3D local cosine over the cross-section's (r_1 = sqrt(1 - q^2); 1 in flatland)
  double eta = 1.5;      // the real index ratio (Fresnel)
  bool all_tir = false;  // 3D, eta < |q|: medium 2 has no direction with the axis component q
};

// Flatland: the light at theta_i, directions and Fresnel at eta.
inline DielectricSection flatland_section(double theta_i, double eta) {
  DielectricSection s;
  s.tau = theta_i;
  s.eta = s.eta_dir = eta;
  return s;
}

// 3D: the groove's cross-section for light i with i.a = i_a, i.u = i_u (the axis a, u = n x a) and
// i.n = ct; the travel direction's axis component in medium 1 is q = -i_u.
inline DielectricSection lifted_section(double i_a, double i_u, double ct, double eta) {
  DielectricSection s;
  s.c3d = std::sqrt((1.0 - i_u) * (1.0 + i_u));
  s.tau = std::atan2(-i_a, ct);
  s.eta = eta;
  const double q_1 = -i_u;
  const double n2sq = (eta - q_1) * (eta + q_1);
  s.all_tir = !(n2sq > 0.0);
  s.eta_dir = s.all_tir ? 1.0 : std::sqrt(n2sq) / s.c3d;
  return s;
}

}  // namespace vgroove::analytic
